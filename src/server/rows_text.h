// Saving edited rows back to their .rows file.
#pragma once

#include <string>

#include "sfit/rows.h"

namespace sfit::server {

/// Writes `rows` to `path` in the .rows format (docs/rows-format.md), atomically, keeping the
/// comment lines that head the file now (its provenance). Before the first save of a session
/// (`first_save`), the file as it is is copied to path + ".bak". Throws Error(kOutputWrite).
void save_rows(const std::string& path, const Rows& rows, bool first_save);

}  // namespace sfit::server
