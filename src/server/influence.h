// The drag's linear prediction (docs/editor.md, "How a drag is refitted"): the quick refit of
// a drag step is least squares at the counts, knots and parameters of the full fit the drag
// started from, frozen for the drag (sfit/frozen_refit.h), a LINEAR map of the data. Moving point k
// by d then moves every control point (i, j) by g_k(i, j) d, where g_k is the fit of data that are
// zero but for 1 at point k (the same number for x, y and z). The page asks for g_k when a point is
// selected and draws S0 + g_k d itself at every pointer move, with no request on the critical path;
// the server's answers for the same moves replace it when they arrive.
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
/// Linear wherever the session's frozen refit can be made (Session::frozen(): not for weighted
/// rows, rows the fit reordered, too many control points) and no drag is under way; checked:
/// a move of the point by (h, 2h, -h) refitted must move the control points by g times it on
/// x, y and z (1e-9 of g's largest value). Error kUsage for a point that does not exist.
nlohmann::json drag_influence(const Session& session, std::size_t row, std::size_t index);

}  // namespace sfit::server
