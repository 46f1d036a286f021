// Reader of points as CSV: "row,x,y,z" with a header, or "x,y,z" rows separated by blank lines.
#pragma once

#include <string>
#include <string_view>

#include "sfit/io/rows_reader.h"

namespace sfit::io {

/// Reads a CSV file of points ("-" reads standard input). Two layouts:
/// - a header naming the columns, among them `x`, `y`, `z` and `row` (any order, any case,
///   extra columns ignored): each point's row is its `row` value; a row's points are
///   consecutive lines with the same value (a value seen again after another row is an error);
/// - `x,y,z` (with or without a header line `x,y,z`): a blank line separates rows, as in .rows.
/// A `weight` (or `w`) column, or a 4th field without a header, is each point's weight
/// (docs/seams.md): a finite number > 0 on every line.
/// Separators: comma or semicolon; quoted header names and a UTF-8 BOM are accepted; '#'
/// starts a comment line; CRLF line ends are accepted.
/// Throws Error with file:line:column as read_rows() does: kInputUnreadable, kInputSyntax
/// (not a number, wrong column count, header without x/y/z, a row split in two),
/// kInputData (NaN, infinity, no points).
RowsFile read_csv(const std::string& path);

/// Parses CSV text held in memory; `name` is used in messages.
RowsFile parse_csv(std::string_view text, const std::string& name);

}  // namespace sfit::io
