// Tensor-product least squares on given knot vectors (corner and adaptive knots). Private.
//
// PURPOSE  The surface of non-uniform knots that the corner knots (corner_knots.h) and the
//          adaptive knots (adaptive_knots.h) try: one solve, over every point.
// METHOD   Control point (i, j) is unknown i nv + j. Each point (u per point, v per row) is one
//          equation of its (p+1)(q+1) basis products; `ridge` times the second differences of
//          the net along u (stride nv; around the wrap where u is closed) and along v (first
//          differences at degree 1) are equations too. They go into the banded Givens QR
//          (banded_lsq.h) in the order of their first unknown, so each stops rotating at the
//          first row of R still empty (in the data's order the rows fill R ahead of them and
//          each costs the band's width times the unknowns). A closed u's wrap (i mod nu) is the
//          cyclic band's (mod nu nv), held in BandedLeastSquares' dense tail.
#pragma once

#include <vector>

#include "sfit/knot_vector.h"
#include "sfit/rows.h"
#include "sfit/surface.h"

namespace sfit::detail {

/// The surface on `ku` (degree p, nu control points; closed where ku is periodic) and `kv`
/// (degree q, nv, open) nearest the points `rows` at parameters u (per point) and v (per row)
/// with the smoothing above, into `s` (data coordinates: `centre` is taken off for the solve
/// and put back). False where the solve failed or a control point is not finite.
bool knot_tensor_lsq(const Rows& rows, const std::vector<double>& u, const std::vector<double>& v,
                     const Point& centre, const KnotVector& ku, int p, int nu, const KnotVector& kv,
                     int q, int nv, double ridge, Surface& s);

}  // namespace sfit::detail
