#include "sfit/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "sfit/error.h"

namespace sfit::io {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw Error(ErrorCode::kOutputWrite, "cannot write output: " + why, Place{.file = path});
}

std::string folder_of(const std::string& path) {
  const std::filesystem::path p(path);
  const auto parent = p.parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

// Creates a unique temporary file next to `path`; returns its name (closed, empty).
std::string make_temporary(const std::string& path) {
  std::string tmpl = path + ".sfit-XXXXXX";
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0) fail(path, std::strerror(errno));
  ::close(fd);
  return tmpl;
}

void sync_file(const std::string& name) {
  const int fd = ::open(name.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

thread_local OutputBatch* open_batch = nullptr;

void rename_onto(const std::string& tmp, const std::string& path) {
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    fail(path, why);
  }
}

void commit(const std::string& tmp, const std::string& path) {
  // Keep the permissions of an existing target; a new file gets the usual 0666 & ~umask.
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    ::chmod(tmp.c_str(), st.st_mode & 07777);
  } else {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::chmod(tmp.c_str(), 0666 & ~mask);
  }
  sync_file(tmp);
  if (OutputBatch::stage(tmp, path)) return;  // renamed by OutputBatch::commit()
  rename_onto(tmp, path);
}

}  // namespace

void check_writable(const std::string& path) {
  if (path.empty()) fail(path, "empty file name");
  const std::string dir = folder_of(path);
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) fail(path, "folder '" + dir + "' does not exist");
  if (!S_ISDIR(st.st_mode)) fail(path, "'" + dir + "' is not a folder");
  if (::access(dir.c_str(), W_OK) != 0) fail(path, "folder '" + dir + "' is not writable");
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) fail(path, "it is a directory");
  // A device, pipe or socket would be replaced by the rename, not written to.
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    fail(path, "it is not a regular file (a device, pipe or socket); give '-' for standard output");
}

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  check_writable(path);
  const std::string tmp = make_temporary(path);
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) fail(path, std::strerror(errno));
      write(out);
      out.flush();
      if (!out) fail(path, "write failed (disk full?)");
    }
    commit(tmp, path);
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

void write_via_temporary(const std::string& path,
                         const std::function<void(const std::string&)>& write) {
  check_writable(path);
  const std::string tmp = make_temporary(path);
  try {
    write(tmp);
    struct stat st {};
    if (::stat(tmp.c_str(), &st) != 0 || st.st_size == 0) fail(path, "the writer produced nothing");
    commit(tmp, path);
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

OutputBatch::OutputBatch() {
  if (open_batch)
    throw Error(ErrorCode::kInternal, "an output batch is already open on this thread");
  open_batch = this;
}

OutputBatch::~OutputBatch() {
  if (open_batch == this) open_batch = nullptr;
  if (!committed_)
    for (const auto& [tmp, path] : staged_) std::remove(tmp.c_str());
}

bool OutputBatch::stage(const std::string& temporary, const std::string& target) {
  if (!open_batch) return false;
  open_batch->staged_.emplace_back(temporary, target);
  return true;
}

void OutputBatch::commit() {
  if (open_batch == this) open_batch = nullptr;
  committed_ = true;
  for (std::size_t i = 0; i < staged_.size(); ++i) {
    try {
      rename_onto(staged_[i].first, staged_[i].second);
    } catch (...) {
      for (std::size_t k = i + 1; k < staged_.size(); ++k) std::remove(staged_[k].first.c_str());
      throw;
    }
  }
  // Make the renames durable too: sync each target folder once.
  std::vector<std::string> folders;
  for (const auto& [tmp, path] : staged_) {
    const std::string dir = folder_of(path);
    if (std::find(folders.begin(), folders.end(), dir) != folders.end()) continue;
    folders.push_back(dir);
    sync_file(dir);
  }
}

}  // namespace sfit::io
