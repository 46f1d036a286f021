// The explicit check of every data point against the finished surface (docs/method.md
// section 6: the gap the paper admits in its section 3.4).
#pragma once

#include <span>

#include "sfit/rows.h"
#include "sfit/surface.h"

namespace sfit {

struct DeviationCheck {
  Point max_deviation = Point::Zero();  ///< max over all points of |S(u,v) - D| per axis
  long worst_row = -1;                  ///< the point that uses most of its tolerance
  long worst_index = -1;
  Point worst_deviation = Point::Zero();  ///< S(u,v) - D there, signed (its direction)
  double worst_ratio = 0;                 ///< max over points and axes of |S - D| / T
  bool within = true;  ///< every point within tolerance per axis (round-off at T = 0)
};

/// Evaluates the surface at every data point's assigned parameters (u per point, in the
/// order of rows.points(); v per row, or per point where v.size() != rows.size(), as
/// FitResult::v_for_points()) and measures the per-axis deviation.
/// A point is within if |S - D|_a <= tolerance_a on every axis a, where a tolerance of 0 allows
/// `roundoff` (the round-off allowance applies at T = 0 only).
/// `threads` (0: all cores) splits the rows into fixed blocks; the result is the same for any
/// thread count.
DeviationCheck check_deviation(const Surface& surface, const Rows& rows, std::span<const double> u,
                               std::span<const double> v, const Point& tolerance, double roundoff,
                               int threads = 1);

}  // namespace sfit
