// Re-representation of a row curve on the common control-point count (docs/method.md section 4),
// with the explicit per-point check and repair that the paper lacked (its section 3.4).
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "sfit/curve_fit.h"

namespace sfit {

struct Rerepresentation {
  Curve curve;                          ///< degree and count of the common knot vector
  std::vector<double> parameters;       ///< parameter of each data point on `curve`
  Point max_deviation = Point::Zero();  ///< max_k |curve(parameters_k) - D_k| per axis
  bool holds = false;                   ///< every data point within the bound
  int repair_rounds = 0;                ///< 0: the paper's re-representation already held
};

/// Re-represents `fit` (a curve fitted to `data`) as a uniform curve of `degree` with `count`
/// control points (docs/method.md 4): samples the old curve at count parameters of the paper's
/// rule and interpolates them at the new Greville abscissae. Each data point gets the new
/// parameter `target_parameters[k]`, or, when that is empty, the image of its old parameter
/// under ReparameterMap (the scaled map when fit.scaled: docs/method.md 7.4).
///
/// Guarantee (beyond the paper): every data point is then checked against `bound` per axis.
/// Where interpolating the samples pushed points out, those points are added to the system as
/// heavily weighted equations (weight raised x1000 a round, at most 8 rounds), which tends to
/// the samples' least-squares curve constrained to pass through them. `holds` says whether
/// all points ended within `bound`; when it is false the caller must raise `count`.
/// A pole (fit.curve.degree == 0) becomes `count` coincident control points.
/// With Resampling::kArcLength (open curves) sample l is the point at arc length fraction
/// tau_l / tau_last along the old curve, and each data point's new parameter is the image of
/// its old one under the piecewise-linear map of those samples onto g_l.
Rerepresentation rerepresent(const CurveFit& fit, std::span<const Point> data, int degree,
                             int count, bool periodic, const Point& bound,
                             std::span<const double> target_parameters = {},
                             Resampling resampling = Resampling::kPaper);

}  // namespace sfit
