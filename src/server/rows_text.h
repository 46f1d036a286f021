// The text of an edited .rows file: the rows (with their weight column where the rows carry
// weights) under the head of the file they replace (a UTF-8 byte-order mark and the leading
// comment lines: its provenance).
#pragma once

#include <string>
#include <string_view>

#include "sfit/rows.h"

namespace sfit::server {

/// The .rows text (docs/rows-format.md) of `rows` under the head of `original` (the file's
/// current bytes): its byte-order mark, if any, and every line before the first data line
/// that is blank or a `#` comment, verbatim. Lines end as `original`'s first line does
/// (CRLF or LF). Weighted rows are written `x y z w`, every number in the fewest digits that
/// read back to the same double.
std::string rows_text(const Rows& rows, std::string_view original);

}  // namespace sfit::server
