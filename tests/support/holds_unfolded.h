// A fit's surface checked independently of the fit's own report: T at every point by the
// reference evaluator, every 7th point within T of the surface by a closest-point search, and
// no fold across (below_points_test.cpp, below_points_lidar_test.cpp).
#pragma once

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::test {

/// T at every point by the independent evaluator at the points' own (u, v), every 7th point
/// within T of the surface by an independent closest-point search (T's x), and no fold on
/// columns sampled 4 times per knot span across; the report's fold 0 and within_tolerance.
void expect_holds_unfolded(const FitResult& f, const Rows& rows, const Point& tol);

}  // namespace sfit::test
