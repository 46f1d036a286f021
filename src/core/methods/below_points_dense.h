// The fallback's third pass below the points (docs/method.md 7.12): the base surface's
// fractions stretched, one monotone map along u and one along v shared by every row, where the
// nearest pair missed T, so that uniform knots in the stretched parameters are knots placed
// densely there and sparsely elsewhere. Private to the surface method.
#pragma once

#include <vector>

#include "below_points_pair.h"
#include "search_frame.h"

namespace sfit::detail {

/// Each point's deviation from the pair `t` (nu x nv, solved at t.fu, t.fv with `spec`) as
/// its worst |S - D| / T over the axes with T > 0, in rows.points() order.
std::vector<double> miss_ratios(const Frame& fr, const ScatteredSpec& spec, const Tried& t, int nu,
                                int nv);

/// Stretches the fractions `fu` (all of them, one map) where the points with `ratio` > 1 are:
/// the map's slope is at least 1 everywhere and at least a point's miss ratio within one knot
/// span (1 / `spans` of the range) of it, falling linearly to 1 at two spans; the map is then
/// scaled back onto [0, 1]. A span there becomes about 1 / ratio of the others after the
/// rescaling (the knot density the miss asks for, in proportion), and the map is monotone, so
/// the rows keep their order and their places relative to each other along the direction.
/// Unchanged where no point misses.
void stretch_where_missed(const std::vector<double>& ratio, int spans, std::vector<double>& fu);

}  // namespace sfit::detail
