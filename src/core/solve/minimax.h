// The minimax (L-infinity) fit at a pair of counts (docs/control-points.md). Private.
//
// PURPOSE  min over the control points of max_k |S(u_k, v_k) - D_k|, per axis, for a surface
//          with given counts, knots and parameters: where least squares misses T by a little,
//          the minimax surface at the same pair may hold it (docs/method.md, the minimax norm).
// METHOD   A linear program per axis (min t subject to -t <= S(u_k, v_k) - D_k <= t), solved
//          by CLP's dual simplex on an active set of points: the points least squares fits
//          worst, then, round by round, every point the minimax surface of the set misses by
//          more than its t, until none does (an exchange method, as Remez's). A naive
//          iteratively reweighted least squares (Lawson) stalls; the LP is exact.
#pragma once

#include <vector>

#include "sfit/rows.h"
#include "sfit/surface.h"

namespace sfit::detail {

/// Replaces the control points of `s` (started from its least-squares fit) by the minimax
/// ones on `rows` at parameters u (per point) and v (per row), axis by axis (an axis that
/// least squares holds keeps its fit). Stops early, returning false, once an axis's minimax
/// error is known to exceed its tolerance (no surface then); true otherwise.
bool minimax_refine(const Rows& rows, const std::vector<double>& u, const std::vector<double>& v,
                    const Point& tolerance, Surface& s);

/// The same with one v per point (v: rows.total_points() values, the geometric rule's), where
/// the coefficients the data hold weakly (below 5 % of the mean data term) keep their values
/// from `s` (the LP has no smoothness term to decide them).
bool minimax_refine_points(const Rows& rows, const std::vector<double>& u,
                           const std::vector<double>& v, const Point& tolerance, Surface& s);

/// Whether a minimax fit of this size is worth its cost inside the search.
bool minimax_affordable(std::size_t points, int nu, int nv);

}  // namespace sfit::detail
