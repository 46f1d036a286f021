// A B-spline curve on uniform knots: clamped (open) or periodic (closed).
#pragma once

#include <vector>

#include "sfit/rows.h"

namespace sfit {

/// B-spline curve of `degree` with uniform knots (docs/method.md section 2). For a periodic curve
/// `control` holds the n distinct control points; the knots are implied by degree and count.
struct Curve {
  int degree = 3;
  bool periodic = false;
  std::vector<Point> control;

  int count() const { return static_cast<int>(control.size()); }
  /// Domain is [0, domain_end()].
  double domain_end() const;
  /// Full knot vector (docs/surface-json.md storage for periodic curves).
  std::vector<double> knots() const;
  /// C(t); t is clamped into (open) or wrapped around (periodic) the domain.
  Point evaluate(double t) const;
  /// The `order`-th derivative dC/dt at t (order 0 is evaluate()).
  Point derivative(double t, int order) const;
};

}  // namespace sfit
