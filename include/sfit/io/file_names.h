// File-name helpers shared by the readers, the writers and the CLI.
#pragma once

#include <cstdint>
#include <string>

namespace sfit::io {

/// Lower-case extension of `path` without the dot ("json", "step", ...); "" if the last
/// path component has no dot.
std::string extension_of(const std::string& path);

/// What a path names, for "is this the same file" whatever the spelling (./a, d/../a, a hard
/// or symbolic link): an existing file is its device and inode; a path that does not exist
/// yet is its folder's device and inode and its last component. Equal identities are one
/// file. `known` is false when not even the folder exists (then nothing can collide).
struct FileIdentity {
  bool known = false;
  bool exists = false;
  std::uint64_t device = 0, inode = 0;
  std::string leaf;  ///< last component, for a path that does not exist
  bool operator==(const FileIdentity&) const = default;
};
FileIdentity identify_file(const std::string& path);
/// The file behind an open descriptor (0: standard input when it is redirected from a file).
FileIdentity identify_descriptor(int fd);

}  // namespace sfit::io
