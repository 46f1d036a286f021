// Parameters of the data points on a curve of a given count (docs/method.md section 3 step 3,
// 7.4) and the re-representation map between two uniform curves (docs/method.md section 4
// step 1). Private to the core and its tests; implemented in parametrization.cpp.
#pragma once

#include <span>
#include <vector>

#include "sfit/parametrization.h"

namespace sfit {

/// Parameters of points at `positions` (normalized_positions()) on a uniform curve of
/// `degree` with `count` control points: t = f (count - degree) open, and for closed curves
/// t = o + f count with the offset o of the periodic Greville rule (0 for odd, 1/2 for even
/// degree). Uniform positions of a closed row give paper_parameters() (to rounding).
std::vector<double> scaled_parameters(int degree, int count, bool periodic,
                                      std::span<const double> positions);

/// The paper's parameters t_0 ... t_{n_points-1} of the points of one row, for a curve of
/// `degree` with `count` control points.
/// Open: the Greville sequence read at the fractional index (count-1) j / (n_points-1), so
/// t_0 = 0 and t_last = count - degree, and with count == n_points the t are the Greville
/// abscissae. Closed (the periodic Greville rule of docs/method.md 7.3): t_j = o + j count /
/// n_points with o = 0 for odd and 1/2 for even degree, so that count == n_points collocates
/// at the Greville abscissae and never at the knots of an even degree.
std::vector<double> paper_parameters(int degree, int count, bool periodic, int n_points);

/// The map from the parameter domain of a curve (degree_from, count_from) to that of the
/// curve it is re-represented as (degree_to, count_to): the paper samples the old curve at
/// tau_l (its Greville sequence read at fractional index l (count_from-1)/(count_to-1)) and
/// places those samples at the new Greville abscissae g_l. This map sends tau_l to g_l and is
/// linear in between (exactly linear for periodic curves).
/// With `scaled` (curves fitted at scaled_parameters(), docs/method.md 7.4) the map is the linear
/// scaling of one domain onto the other, which keeps a point's position f, and tau_l is the
/// preimage of g_l; for periodic curves the two coincide.
class ReparameterMap {
 public:
  ReparameterMap(int degree_from, int count_from, int degree_to, int count_to, bool periodic,
                 bool scaled = false);
  /// Parameter on the new curve of parameter t on the old one.
  double operator()(double t) const;
  /// The sample parameters tau_l on the old curve (count_to of them).
  const std::vector<double>& samples() const { return tau_; }
  /// The new Greville abscissae g_l the samples are placed at.
  const std::vector<double>& targets() const { return g_; }

 private:
  bool periodic_, scaled_ = false;
  double scale_ = 1, offset_from_ = 0, offset_to_ = 0, period_to_ = 1;
  std::vector<double> tau_, g_;
};

}  // namespace sfit
