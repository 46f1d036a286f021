// Opening an input file with the readers' common errors (private to sfit_io).
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

namespace sfit::io::detail {

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f && f != stdin) std::fclose(f);
  }
};
using InputFile = std::unique_ptr<std::FILE, FileCloser>;

/// Opens `path` for binary reading; "-" is standard input. `size` (if given) receives the
/// file's size in bytes (0 for standard input). Throws Error(kInputUnreadable) naming the
/// path and the reason: missing, unreadable, or a directory.
InputFile open_input(const std::string& path, std::uint64_t* size = nullptr);

}  // namespace sfit::io::detail
