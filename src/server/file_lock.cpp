#include "file_lock.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <fstream>
#include <string>

namespace sfit::server {
namespace {

// The process id written in the lock file, or -1 if unreadable.
long holder_of(const std::string& path) {
  std::ifstream in(path);
  long pid = -1;
  if (!(in >> pid) || pid <= 0) return -1;
  return pid;
}

bool alive(long pid) {
  return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
}

// Creates `path` exclusively with our process id; false if it exists (errno EEXIST).
bool create(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return false;
  const std::string text = std::to_string(static_cast<long>(::getpid())) + "\n";
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  if (!ok) ::unlink(path.c_str());
  return ok;
}

}  // namespace

FileLock::FileLock(const std::string& input) : path_(input + ".sfit-lock") {
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (create(path_)) {
      owned_ = true;
      return;
    }
    if (errno != EEXIST) {
      why_ = "cannot make the lock file " + path_ +
             ": another editor of this file would not be warned";
      return;
    }
    long pid = holder_of(path_);
    if (pid < 0) {  // being written this instant: look once more
      ::usleep(50'000);
      pid = holder_of(path_);
    }
    if (pid < 0) {
      writable_ = false;
      why_ = path_ + " exists but names no process: another sfit edit may be editing this " +
             "file; opened read-only (remove it if it is stale)";
      return;
    }
    if (alive(pid)) {
      writable_ = false;
      why_ = "another sfit edit (process " + std::to_string(pid) +
             ") is editing this file: opened read-only (save is off; edits stay in this session " +
             "and can be exported). " + "Close the other editor, or remove " + path_ +
             " if it is stale, and reopen.";
      return;
    }
    ::unlink(path_.c_str());  // a stale lock: its process is gone
  }
  writable_ = false;
  why_ = "cannot take the lock " + path_ + ": opened read-only";
}

FileLock::~FileLock() {
  if (owned_ && holder_of(path_) == static_cast<long>(::getpid())) ::unlink(path_.c_str());
}

}  // namespace sfit::server
