// Deviations of data points from a surface, for the deviation picture: at the parameters the
// fit assigned (what the report measures), or at the closest surface point (when only the
// surface and the data are known).
#pragma once

#include <span>
#include <vector>

#include "sfit/rows.h"
#include "sfit/surface.h"

namespace sfit::render {

/// S(u_k, v_row(k)) - D_k for every data point (u per point in rows.points() order, v per row,
/// or per point where v.size() is the points' number: FitResult::v_for_points()), exactly as
/// check_deviation() measures them.
std::vector<Point> deviations_at_parameters(const Surface& surface, const Rows& rows,
                                            std::span<const double> u, std::span<const double> v);

/// The surface point nearest a data point.
struct ClosestPoint {
  double u = 0, v = 0;
  Point deviation = Point::Zero();  ///< S(u, v) - D
};

/// For each point, the nearest point of the surface: from each of the 6 nearest samples of a
/// grid of 4 samples per knot span (found through a bucket grid), Newton's method on
/// |S(u,v) - D|^2 with a line search, held to the domain (wrapped where periodic); the best
/// result wins. Several starts keep a point near a thin edge on its own side.
/// |deviation| is never more than the distance at the assigned parameters, so the per-axis
/// values are a lower bound of what the fit report measured in the usual case.
std::vector<ClosestPoint> closest_points(const Surface& surface, std::span<const Point> points);

/// v of each row estimated from its points' closest points (the median; on a periodic v the
/// median of the values unwrapped around the first point's v).
std::vector<double> row_parameters(const Surface& surface, const Rows& rows,
                                   std::span<const ClosestPoint> closest);

/// max over axes of |d_a| / T_a: 1 means the point uses its whole tolerance. Axes with
/// T_a = 0 count d_a / `zero_scale` (so an interpolating fit can still be coloured).
double tolerance_ratio(const Point& deviation, const Point& tolerance, double zero_scale);

}  // namespace sfit::render
