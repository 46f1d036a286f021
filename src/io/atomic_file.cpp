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

#include "atomic_file_testing.h"
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

// The tests' injected rename failure (atomic_file_testing.h): the index of the batch rename
// to fail and its errno; -1: none.
int injected_rename = -1;
int injected_errno = 0;

// Why replacing or creating `path` by a rename in its folder would fail, or "" if it can:
// the folder missing, not a folder or not writable, `path` a directory, or `path` someone
// else's file in a sticky folder (/tmp), which only its owner (or the folder's) may replace.
std::string rename_blocker(const std::string& path) {
  const std::string dir = folder_of(path);
  struct stat d {};
  if (::stat(dir.c_str(), &d) != 0) return "folder '" + dir + "' does not exist";
  if (!S_ISDIR(d.st_mode)) return "'" + dir + "' is not a folder";
  if (::access(dir.c_str(), W_OK | X_OK) != 0) return "folder '" + dir + "' is not writable";
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "";
  if (S_ISDIR(st.st_mode)) return "it is a directory";
  const uid_t me = ::geteuid();
  if ((d.st_mode & S_ISVTX) && me != 0 && st.st_uid != me && d.st_uid != me)
    return "it belongs to another user (uid " + std::to_string(st.st_uid) +
           ") in the sticky folder '" + dir + "', where only its owner may replace it";
  return "";
}

// A copy of the existing `path` under a fresh temporary name beside it (a hard link, else a
// copy of its content and mode; a symbolic link is linked again): "" if it cannot be made.
std::string keep_aside(const std::string& path) {
  std::string aside = path + ".sfit-XXXXXX";
  const int fd = ::mkstemp(aside.data());
  if (fd < 0) return "";
  ::close(fd);
  ::unlink(aside.c_str());
  if (::link(path.c_str(), aside.c_str()) == 0) return aside;
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "";
  if (S_ISLNK(st.st_mode)) {
    std::string to(static_cast<std::size_t>(st.st_size) + 1, '\0');
    const ssize_t n = ::readlink(path.c_str(), to.data(), to.size());
    if (n < 0 || static_cast<std::size_t>(n) >= to.size()) return "";
    to.resize(static_cast<std::size_t>(n));
    return ::symlink(to.c_str(), aside.c_str()) == 0 ? aside : "";
  }
  std::ifstream in(path, std::ios::binary);
  std::ofstream out(aside, std::ios::binary | std::ios::trunc);
  if (!in || !out || !(out << in.rdbuf()) || !out.flush()) {
    out.close();
    std::remove(aside.c_str());
    return "";
  }
  out.close();
  ::chmod(aside.c_str(), st.st_mode & 07777);
  sync_file(aside);
  return aside;
}

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
  if (const std::string why = rename_blocker(path); !why.empty()) fail(path, why);
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
  const std::size_t n = staged_.size();
  std::vector<std::string> aside(n);   // each replaced target's old content, for the roll-back
  auto drop = [&](std::size_t from) {  // the temporaries from `from` on, and every copy aside
    for (std::size_t k = from; k < n; ++k) std::remove(staged_[k].first.c_str());
    for (const std::string& a : aside)
      if (!a.empty()) std::remove(a.c_str());
  };
  // Before the first rename: every rename can succeed (a folder made read-only meanwhile, a
  // directory in the way, someone else's file in a sticky folder); and each target that a
  // later rename's failure would have to restore is kept aside.
  for (std::size_t i = 0; i < n; ++i) {
    const std::string& path = staged_[i].second;
    const std::string why = rename_blocker(path);
    if (!why.empty()) {
      drop(0);
      fail(path, why);
    }
    struct stat st {};
    if (i + 1 < n && ::lstat(path.c_str(), &st) == 0) {
      aside[i] = keep_aside(path);
      if (aside[i].empty()) {
        const std::string err = std::strerror(errno);
        drop(0);
        fail(path, "cannot keep its old content aside for a roll-back (" + err + ")");
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto& [tmp, path] = staged_[i];
    int err = 0;
    if (static_cast<int>(i) == injected_rename) {
      injected_rename = -1;
      err = injected_errno;
    } else if (std::rename(tmp.c_str(), path.c_str()) != 0) {
      err = errno;
    }
    if (err == 0) continue;
    // Roll back: every target renamed before this one gets its old content (or goes again).
    std::string undone;
    for (std::size_t k = i; k-- > 0;) {
      const std::string& t = staged_[k].second;
      const bool ok = aside[k].empty() ? std::remove(t.c_str()) == 0
                                       : std::rename(aside[k].c_str(), t.c_str()) == 0;
      if (ok)
        aside[k].clear();
      else
        undone += (undone.empty() ? "" : ", ") + t;
    }
    drop(i);
    fail(path, std::string(std::strerror(err)) +
                   (i == 0           ? ""
                    : undone.empty() ? "; the outputs renamed before it were restored"
                                     : "; could not restore " + undone));
  }
  for (std::string& a : aside)
    if (!a.empty()) std::remove(a.c_str());
  // Make the renames durable too: sync each target folder once.
  std::vector<std::string> folders;
  for (const auto& [tmp, path] : staged_) {
    const std::string dir = folder_of(path);
    if (std::find(folders.begin(), folders.end(), dir) != folders.end()) continue;
    folders.push_back(dir);
    sync_file(dir);
  }
}

namespace testing {
void fail_rename_at(int k, int error) {
  injected_rename = k;
  injected_errno = error;
}
}  // namespace testing

}  // namespace sfit::io
