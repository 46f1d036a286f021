// Writing outputs so that nothing is lost: a temporary file in the target folder, renamed
// over the target only once it is complete.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace sfit::io {

/// Writes `path` through a temporary file "path.sfit-XXXXXX" in the same folder: `write`
/// fills the stream, the file is flushed and fsync'ed, then renamed onto `path`. On any
/// failure the temporary file is removed, an existing `path` is untouched, and
/// Error(kOutputWrite) names the path and the reason.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

/// For writers that only take a file name (OpenCASCADE, libpng): `write` gets the temporary
/// path to create; it is renamed onto `path` when `write` returns without throwing.
void write_via_temporary(const std::string& path,
                         const std::function<void(const std::string& temporary)>& write);

/// Throws Error(kOutputWrite) if `path` cannot be created: its folder is missing or not
/// writable, or it is a directory, or it exists and is not a regular file (a device such as
/// /dev/null, a pipe: the rename would replace it), or it is another user's file in a sticky
/// folder such as /tmp (only its owner may replace it). Lets the CLI refuse before a long fit.
void check_writable(const std::string& path);

/// All or nothing for several outputs. While a batch is open on this thread,
/// write_file_atomically() and write_via_temporary() leave each complete, fsync'ed file under
/// its temporary name beside its target; commit() renames every one onto its target. A batch
/// destroyed without commit() (a later output failed, a disk filled up) removes every
/// temporary, so each target is exactly as it was and no new file appears. Batches do not
/// nest. commit() first checks that every rename can succeed (check_writable() again: a
/// folder made read-only meanwhile, someone else's file in a sticky folder) and keeps each
/// replaced target's old content aside (a hard link, else a copy); if a rename still fails,
/// the targets renamed before it get their old content back (new ones are removed) and
/// Error(kOutputWrite) names the target whose rename failed.
class OutputBatch {
 public:
  OutputBatch();
  ~OutputBatch();
  OutputBatch(const OutputBatch&) = delete;
  OutputBatch& operator=(const OutputBatch&) = delete;
  /// Renames every staged temporary onto its target, in the order they were written.
  void commit();
  /// Used by the writers: true if a batch is open on this thread, and stages (tmp, target).
  static bool stage(const std::string& temporary, const std::string& target);

 private:
  std::vector<std::pair<std::string, std::string>> staged_;  // (temporary, target)
  bool committed_ = false;
};

}  // namespace sfit::io
