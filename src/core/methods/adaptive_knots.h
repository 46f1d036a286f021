// Knots where the shape needs them (docs/method.md, "Adaptive knots"): beside the uniform
// surface search, a surface on non-uniform knots placed where the residuals concentrate,
// kept only when it has strictly fewer control points, holds T at every point and does not
// fold. Private to fit_surface().
//
// PURPOSE  Fewer control points where the data has corners (a deck edge, a chine) or a local
//          feature: uniform knots must be as dense everywhere as the hardest place needs.
// METHOD   The points keep the uniform fit's parameters (u per point, v per row) and domain.
//          1. Knots along u, common to every row: from a coarse uniform vector, each row is
//             fitted alone on them (least squares); every span where some row misses a
//             fraction of T gets a knot at its worst point's u (again at the same u, up to the
//             degree's multiplicity, where the worst point sits on a knot: a corner becomes a
//             C^0 crease), until every row holds that fraction.
//          2. Knots along v: from a coarse uniform vector, the tensor-product least squares
//             over all points on (u knots, v knots); a v span holding a missed point gets a
//             knot midway (while the span holds two rows or more), a u span otherwise, until
//             every point holds T.
//          3. Knot removal: each inserted u knot, then each v knot, is taken out where the
//             surface without it still holds T at every point.
//          A small second-difference term keeps every solve defined where a span has few
//          points; the final check (every point, per axis) decides, as for every surface.
//          Closed rows (periodic u): periodic breakpoints, b_0 a knot like the others (kept at
//          multiplicity 1 at least: the points keep their u), solves whose u basis wraps (the
//          cyclic band of BandedLeastSquares).
// LIMITS   One v per row and an open v direction only (per-point v and a closed v stay
//          uniform); sets whose solves would cost much more than the uniform search skip it.
#pragma once

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

/// Replaces `result`'s surface (and its report's counts, deviations and knots) by one on
/// adapted knots when that is strictly smaller, holds T and does not fold; true if it did.
bool adapt_knots(const Rows& rows, const FitOptions& options, FitResult& result);

}  // namespace sfit::detail
