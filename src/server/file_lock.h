// One editor per file: `sfit edit INPUT` holds INPUT.sfit-lock (its process id) while it runs.
// A second editor of the same file finds the lock held by a live process and opens read-only
// (it may look, fit and export, never save), so two sessions never overwrite each other's
// saves or the first session's INPUT.bak. A lock left by a process that no longer runs (a
// crash) is taken over.
#pragma once

#include <string>

namespace sfit::server {

class FileLock {
 public:
  /// Tries to take `input`.sfit-lock; never throws (a lock that cannot be made, e.g. in a
  /// read-only folder, leaves the session writable and says so in why()).
  explicit FileLock(const std::string& input);
  ~FileLock();  ///< removes the lock file if this process made it
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

  /// True if this process holds the lock (or none could be made): saving is allowed.
  bool writable() const { return writable_; }
  /// Empty, or why the session is read-only / unlocked, for the page to show.
  const std::string& why() const { return why_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  bool owned_ = false, writable_ = true;
  std::string why_;
};

}  // namespace sfit::server
