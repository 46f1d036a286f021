// One number of a .rows or .csv line (src/io). Private.
#pragma once

#include <fast_float/fast_float.h>

#include <charconv>
#include <cmath>

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

}  // namespace sfit::io::detail
