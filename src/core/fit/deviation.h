// The explicit check of every data point against the finished surface (docs/method.md
// section 6: the gap the paper admits in its section 3.4).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "basis_knots.h"
#include "sfit/rows.h"
#include "sfit/surface.h"

namespace sfit {

/// S at a point whose u basis is known (`bu` from eval_basis(), its first index `fu`) and
/// whose v is its own (a per-point v, FitResult::v_points): the checks' arithmetic where no
/// iso-curve of the row can be shared.
inline Point point_at(const Surface& s, const double* bu, int fu, double v) {
  std::array<double, kMaxDegree + 1> bv;
  const int fw = basis_v(s, v, bv.data());
  Point p = Point::Zero();
  for (int a = 0; a <= s.degree_u; ++a) {
    Point q = Point::Zero();
    for (int b = 0; b <= s.degree_v; ++b)
      q += bv[b] * s.at(wrap_index(fu + a, s.count_u), wrap_index(fw + b, s.count_v));
    p += bu[a] * q;
  }
  return p;
}

struct DeviationCheck {
  Point max_deviation = Point::Zero();  ///< max over all points of |S(u,v) - D| per axis
  long worst_row = -1;                  ///< the point that uses most of its tolerance
  long worst_index = -1;
  Point worst_deviation = Point::Zero();  ///< S(u,v) - D there, signed (its direction)
  double worst_ratio = 0;                 ///< max over points and axes of |S - D| / T
  bool within = true;  ///< every point within tolerance per axis (round-off at T = 0)
};

/// The largest of |d_a| / t_a over the axes (every t_a > 0): how much of T a deviation uses.
inline double max_axis_ratio(const Point& d, const Point& t) {
  return std::max({std::abs(d.x()) / t.x(), std::abs(d.y()) / t.y(), std::abs(d.z()) / t.z()});
}

/// The check's deviations and worst point into a report (FitReport: its max_deviation,
/// worst_row, worst_index and worst_deviation).
template <class Report>
void report_deviation(Report& rep, const DeviationCheck& c) {
  rep.max_deviation = c.max_deviation;
  rep.worst_row = c.worst_row;
  rep.worst_index = c.worst_index;
  rep.worst_deviation = c.worst_deviation;
}

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
