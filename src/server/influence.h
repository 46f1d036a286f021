// The drag's linear prediction (docs/editor.md, "Latency"): with the counts held and
// parameters that do not move with the points, the quick refit of a drag step is least
// squares at fixed counts, knots and parameters, a LINEAR map of the data. Moving point k by
// d then moves every control point (i, j) by g_k(i, j) d, where g_k is the fit of data that
// are zero but for 1 at point k (the same number for x, y and z). The page asks for g_k once
// when a point is selected and draws S0 + g_k d itself at every pointer move, with no request
// on the critical path; the server's answers for the same moves replace it when they arrive.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>

#include "session.h"

namespace sfit::server {

/// POST /api/influence {"row", "index"}: {"version", "row", "index", "linear"} and, where the
/// session's quick refit is linear in the moved point, "point" (its position now),
/// "surface" (the quick refit of the rows as they are, S0: the contract with its control
/// points packed exactly, "control_points_f64") and "influence" (base64 of the
/// little-endian doubles g(i, j), in the order of S0's packed control points); else "why".
/// Linear: the surface method at held counts by least squares (quick_refit_options()), the
/// parameters uniform or paper (their u and v do not depend on where the points are), open
/// rows or seams kept, no weights, uniform knots, no drag under way; and checked: g from a
/// move of the point by (h, 2h, -h) must agree on x, y and z (1e-9 of its largest value) and
/// keep the surface's shape. Error kUsage for a point that does not exist.
nlohmann::json drag_influence(const Session& session, std::size_t row, std::size_t index);

}  // namespace sfit::server
