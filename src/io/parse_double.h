// One number of a .rows or .csv line (src/io). Private.
#pragma once

#include <fast_float/fast_float.h>

#include <locale.h>
#include <stdlib.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "sfit/error.h"
#include "sfit/rows.h"

namespace sfit::io::detail {

/// std::from_chars(b, e, x) for doubles, with its verdicts (ptr, ec) unchanged: the common case,
/// a normal number, by fast_float (Debian's libfast-float-dev: the same correctly rounded
/// result, without the library call); zero, subnormals, infinities, NaN and every error by
/// std::from_chars itself, so the readers' messages for bad and out-of-range numbers stay.
inline std::from_chars_result parse_double(const char* b, const char* e, double& x) {
  const auto r = fast_float::from_chars(b, e, x);
  if (r.ec == std::errc() && std::isnormal(x)) return {r.ptr, r.ec};
  return std::from_chars(b, e, x);
}

/// What one field of a line holds, read by the rule both readers follow: an optional leading
/// '+', then a whole number as std::from_chars reads it; too large (1e400) is out of range,
/// too small (1e-400) underflows to 0 or a subnormal, as strtod; NaN and infinities are not
/// finite.
enum class FieldNumber { kOk, kEmpty, kNotANumber, kOutOfRange, kNotFinite };

inline FieldNumber read_field_number(std::string_view tok, double& x) {
  const char* b = tok.data();
  const char* e = b + tok.size();
  if (b != e && *b == '+') ++b;
  x = 0;
  if (b == e) return tok.empty() ? FieldNumber::kEmpty : FieldNumber::kNotANumber;
  const auto r = parse_double(b, e, x);
  if (r.ec == std::errc::result_out_of_range && r.ptr == e) {
    // strtod in the "C" locale (a host program's decimal comma must not cut "1.5e-400" at
    // its point), the whole field read or it is no number.
    static const locale_t c_locale = newlocale(LC_NUMERIC_MASK, "C", locale_t{});
    const std::string copy(b, e);
    char* end = nullptr;
    x = strtod_l(copy.c_str(), &end, c_locale);
    if (end != copy.c_str() + copy.size()) return FieldNumber::kNotANumber;
    return std::isinf(x) ? FieldNumber::kOutOfRange : FieldNumber::kOk;
  }
  if (r.ec != std::errc() || r.ptr != e) return FieldNumber::kNotANumber;
  return std::isfinite(x) ? FieldNumber::kOk : FieldNumber::kNotFinite;
}

/// A field as an error message shows it: at most 40 characters, control and non-ASCII bytes as
/// \xNN.
inline std::string show_field(std::string_view tok) {
  std::string s;
  for (char c : tok.substr(0, 40)) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", u);
      s += buf;
    } else {
      s += c;
    }
  }
  if (tok.size() > 40) s += "...";
  return s;
}

/// Where a reader stands: file `file`, line `line`, 1-based column `column`, and the row and
/// point the next point would be in `rows` (the rows read so far).
inline Place reading_place(const std::string& file, long line, std::size_t column,
                           const Rows& rows) {
  return Place{.file = file,
               .line = line,
               .column = static_cast<long>(column),
               .row = static_cast<long>(rows.size()),
               .point = static_cast<long>(rows.open_row_size())};
}

/// The error of a field that is no usable number (read_field_number() did not give kOk), with
/// the message both readers give for it; `where` places it (file, line, column, row, point).
[[noreturn]] inline void throw_field_error(FieldNumber what, std::string_view tok,
                                           const Place& where) {
  switch (what) {
    case FieldNumber::kEmpty:
      throw Error(ErrorCode::kInputSyntax, "empty field where a number belongs", where);
    case FieldNumber::kOutOfRange:
      throw Error(ErrorCode::kInputData,
                  "'" + show_field(tok) + "' is out of the range of a double", where);
    case FieldNumber::kNotFinite:
      throw Error(ErrorCode::kInputData, "'" + show_field(tok) + "' is not a finite number", where);
    default:
      throw Error(ErrorCode::kInputSyntax, "'" + show_field(tok) + "' is not a number", where);
  }
}

}  // namespace sfit::io::detail
