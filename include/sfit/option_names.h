// The named values of the fit options, parsed once for every front end (CLI, Python, editor):
// the names and their rules live here, not in each caller.
#pragma once

#include <string>
#include <string_view>

#include "sfit/curve_fit.h"
#include "sfit/fit_limits.h"  // check_tolerance_fraction and the other limits

namespace sfit {

/// "fast", "linear", "known".
std::string_view to_string(CountSearch search);
/// The inverse of to_string(); false if `name` is none of them.
bool parse_count_search(std::string_view name, CountSearch& out);

/// Closed directions by name: "" or "none" (open), "u" (each row a closed contour), "v" (the
/// rows a closed sequence), "uv" or "vu" (both). False if `name` is none of them (the outputs
/// are then unchanged).
bool parse_closed(std::string_view name, bool& closed_u, bool& closed_v);
/// "none", "u", "v" or "uv".
std::string_view closed_to_string(bool closed_u, bool closed_v);

}  // namespace sfit
