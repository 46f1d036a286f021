#include "rows_text.h"

#include <fmt/format.h>

#include <iterator>

namespace sfit::server {
namespace {

constexpr std::string_view kBom = "\xEF\xBB\xBF";

// A line of the head: blank, or a comment (spaces or tabs, then '#').
bool head_line(std::string_view line) {
  for (const char c : line) {
    if (c == ' ' || c == '\t' || c == '\r') continue;
    return c == '#';
  }
  return true;
}

}  // namespace

std::string rows_text(const Rows& rows, std::string_view original) {
  std::string out;
  std::string_view rest = original;
  if (rest.substr(0, kBom.size()) == kBom) {
    out += kBom;
    rest.remove_prefix(kBom.size());
  }
  const std::size_t first_end = rest.find('\n');
  const std::string_view eol =
      first_end != std::string_view::npos && first_end > 0 && rest[first_end - 1] == '\r' ? "\r\n"
                                                                                          : "\n";
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    const std::string_view line = rest.substr(0, end);
    if (!head_line(line)) break;
    out += line;
    out += '\n';
    if (end == std::string_view::npos) break;
    rest.remove_prefix(end + 1);
  }
  // A head whose last line lacks its newline got one above; a CR of a CRLF line stays.
  fmt::memory_buffer b;
  auto it = std::back_inserter(b);
  const bool weighted = rows.weighted();
  for (std::size_t j = 0; j < rows.size(); ++j) {
    if (j > 0) fmt::format_to(it, "{}", eol);
    const auto points = rows[j];
    const auto weights = rows.row_weights(j);
    for (std::size_t k = 0; k < points.size(); ++k) {
      const Point& p = points[k];
      if (weighted)
        fmt::format_to(it, "{} {} {} {}{}", p.x(), p.y(), p.z(), weights[k], eol);
      else
        fmt::format_to(it, "{} {} {}{}", p.x(), p.y(), p.z(), eol);
    }
  }
  out.append(b.data(), b.size());
  return out;
}

}  // namespace sfit::server
