// Saving the edited rows back to the .rows file the editor was started on, safely: through a
// symbolic link to its target, keeping the file's mode and owner, never over a read-only file
// or one with other hard links, and never replacing the backup of the original.
#pragma once

#include <string>

#include "sfit/rows.h"

namespace sfit::server {

struct SaveResult {
  std::string target;           ///< the file written: `input`, or the file its link points to
  std::string backup;           ///< input + ".bak"
  bool backup_written = false;  ///< false: the backup already existed and was kept
};

/// Writes `rows` (docs/rows-format.md; with their weight column where they carry weights)
/// to `input`, atomically: a temporary file beside the file, with its mode and owner, renamed
/// over it. Through a symbolic link the link's target is written and the link stays. The head
/// of the file (byte-order mark, leading comment lines) is kept. Before that, unless
/// input + ".bak" exists in any form, the file as it is now is copied there (created, never
/// replaced: the first backup, the original, survives every later save and session).
/// Refuses, writing nothing, a target that is read-only (no write permission bit, or not
/// writable by this process), not a regular file, or has other hard links (a rename would
/// break them). Throws Error(kOutputWrite, file = input).
SaveResult save_rows(const std::string& input, const Rows& rows);

}  // namespace sfit::server
