// File-name helpers shared by the readers, the writers and the CLI.
#pragma once

#include <string>

namespace sfit::io {

/// Lower-case extension of `path` without the dot ("json", "step", ...); "" if the last
/// path component has no dot.
std::string extension_of(const std::string& path);

}  // namespace sfit::io
