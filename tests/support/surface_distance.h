// Geometric comparison of two fitted surfaces for the seam and fold tests: how far one lies
// from the other, measured by closest points (so a different parametrisation of the same
// shape, e.g. another seam, costs nothing).
#pragma once

#include <vector>

#include "sfit/rows.h"
#include "sfit/surface.h"
#include "sfit/surface_fit.h"

namespace sfit::test {

/// Distance from q to the closest point of `s` (dense grid start, then Gauss-Newton).
double distance_to_surface(const Surface& s, const Point& q);

/// Points of `fit` on dense samples between its rows: `per_span` samples per knot span along
/// u, and `between` samples in each interval between consecutive rows' v (rows included).
std::vector<Point> samples_between_rows(const FitResult& fit, int per_span = 8, int between = 4);

/// max over samples_between_rows(a) of the distance to b.surface, and the same from b to a.
double surface_gap(const FitResult& a, const FitResult& b);

}  // namespace sfit::test
