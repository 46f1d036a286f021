#include "basis_knots.h"

#include "basis_recurrence.h"

namespace sfit {

int eval_basis_knots(const KnotVector& k, double t, double* N) {
  const int s = k.find_span(t);
  const double* U = k.full().data();
  detail::basis_values([U](int m) { return U[m]; }, k.degree(), s, t, N);
  return s - k.degree();
}

int eval_basis_derivatives_knots(const KnotVector& k, double t, int nderiv, double* ders) {
  const int s = k.find_span(t);
  const double* U = k.full().data();
  detail::basis_derivatives([U](int m) { return U[m]; }, k.degree(), s, t, nderiv, ders);
  return s - k.degree();
}

}  // namespace sfit
