// Basis functions of one direction of a Surface on its KnotVector: the uniform functions of
// basis.h (their fast paths, the same bits as before) when the knots are uniform, the
// Cox-de Boor recurrence on the full vector otherwise.
#pragma once

#include "basis.h"
#include "basis_upto.h"
#include "sfit/knot_vector.h"
#include "sfit/surface.h"

namespace sfit {

/// eval_basis() on a non-uniform KnotVector `k` (A2.2 on its full vector).
int eval_basis_knots(const KnotVector& k, double t, double* N);
/// eval_basis_derivatives() on a non-uniform KnotVector (A2.3).
int eval_basis_derivatives_knots(const KnotVector& k, double t, int nderiv, double* ders);

inline int eval_basis(const KnotVector& k, int degree, int count, bool periodic, double t,
                      double* N) {
  return k.uniform() ? eval_basis(degree, count, periodic, t, N) : eval_basis_knots(k, t, N);
}
inline int eval_basis_derivatives(const KnotVector& k, int degree, int count, bool periodic,
                                  double t, int nderiv, double* ders) {
  return k.uniform() ? eval_basis_derivatives(degree, count, periodic, t, nderiv, ders)
                     : eval_basis_derivatives_knots(k, t, nderiv, ders);
}
inline int eval_basis_upto(const KnotVector& k, int degree, int count, bool periodic, double t,
                           int nderiv, double* ders) {
  return k.uniform() ? eval_basis_upto(degree, count, periodic, t, nderiv, ders)
                     : eval_basis_derivatives_knots(k, t, nderiv, ders);
}

/// The basis of a surface along u or v at t (values[0 .. degree]; returns the first index).
inline int basis_u(const Surface& s, double u, double* N) {
  return eval_basis(s.knots_u, s.degree_u, s.count_u, s.periodic_u, u, N);
}
inline int basis_v(const Surface& s, double v, double* N) {
  return eval_basis(s.knots_v, s.degree_v, s.count_v, s.periodic_v, v, N);
}
inline int basis_derivatives_u(const Surface& s, double u, int nderiv, double* ders) {
  return eval_basis_derivatives(s.knots_u, s.degree_u, s.count_u, s.periodic_u, u, nderiv, ders);
}
inline int basis_derivatives_v(const Surface& s, double v, int nderiv, double* ders) {
  return eval_basis_derivatives(s.knots_v, s.degree_v, s.count_v, s.periodic_v, v, nderiv, ders);
}

}  // namespace sfit
