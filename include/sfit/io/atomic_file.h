// Writing outputs so that nothing is lost: a temporary file in the target folder, renamed
// over the target only once it is complete.
#pragma once

#include <functional>
#include <ostream>
#include <string>

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
/// writable, or it is a directory. Lets the CLI refuse before a long fit.
void check_writable(const std::string& path);

}  // namespace sfit::io
