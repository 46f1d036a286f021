// Reader of the .rows text format (docs/rows-format.md): one point "x y z" per line,
// '#' starts a comment, a blank line separates consecutive rows.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "sfit/rows.h"

namespace sfit::io {

/// Rows read from a file, with the line each row starts on (for messages).
struct RowsFile {
  Rows rows;
  std::vector<long> first_line;  ///< 1-based line of the first point of each row
  std::string name;              ///< the path, or "-" for standard input
};

/// The longest line accepted, in bytes (a longer one is an input-syntax error).
inline constexpr std::size_t kMaxLineBytes = 1 << 20;

/// Reads a .rows file ("-" reads standard input), streaming in blocks. A 4th number on a
/// line is the point's weight (docs/seams.md): then every point has one, finite and > 0
/// (kInputSyntax naming file:line where a point has 3 numbers and the first had 4, or the
/// other way round; kInputData for a weight <= 0).
/// Accepted: separators of spaces, tabs and commas; CRLF line ends; a UTF-8 byte-order mark;
/// '#' comments (whole lines or trailing); several consecutive blank lines are one separator.
/// Throws Error: kInputUnreadable (missing, unreadable, a directory), kInputSyntax
/// (file:line:column: not a number, not 3 numbers, line too long), kInputData
/// (file:line:column: NaN, infinity or out of double range; no points at all).
RowsFile read_rows(const std::string& path);

/// Parses .rows text held in memory; `name` is used in messages.
RowsFile parse_rows(std::string_view text, const std::string& name);

}  // namespace sfit::io
