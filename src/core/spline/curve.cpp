#include "sfit/curve.h"

#include <array>

#include "basis.h"
#include "knots.h"

namespace sfit {

double Curve::domain_end() const {
  return sfit::domain_end(degree, count(), periodic);
}

std::vector<double> Curve::knots() const {
  return periodic ? periodic_uniform_knots(degree, count())
                  : clamped_uniform_knots(degree, count());
}

Point Curve::evaluate(double t) const {
  std::array<double, kMaxDegree + 1> b;
  const int n = count();
  const int first = eval_basis(degree, n, periodic, t, b.data());
  Point p = Point::Zero();
  if (first + degree < n) {
    for (int i = 0; i <= degree; ++i) p += b[i] * control[first + i];
  } else {
    for (int i = 0; i <= degree; ++i) p += b[i] * control[wrap_index(first + i, n)];
  }
  return p;
}

Point Curve::derivative(double t, int order) const {
  if (order == 0) return evaluate(t);
  std::array<double, (kMaxDegree + 1) * (kMaxDegree + 1)> d;
  const int n = count();
  const int first = eval_basis_derivatives(degree, n, periodic, t, order, d.data());
  Point p = Point::Zero();
  for (int i = 0; i <= degree; ++i)
    p += d[order * (degree + 1) + i] * control[wrap_index(first + i, n)];
  return p;
}

}  // namespace sfit
