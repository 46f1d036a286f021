// Opening an input file with the readers' common errors (private to sfit_io).
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

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

/// Feeds `text` to `parser` line by line (without the '\n'), calling parser.too_long() for a
/// line longer than `max_line` bytes before parser.line(). The in-memory readers share it.
template <class Parser>
void feed_lines(std::string_view text, std::size_t max_line, Parser& parser) {
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t nl = text.find('\n', start);
    if (nl == std::string_view::npos) nl = text.size();
    if (nl - start > max_line) parser.too_long();
    parser.line(text.substr(start, nl - start));
    start = nl + 1;
  }
}

}  // namespace sfit::io::detail
