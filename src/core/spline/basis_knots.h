// Basis functions of one direction of a Surface on its KnotVector: the uniform functions of
// basis.h (their fast paths, the same bits as before) when the knots are uniform, the
// Cox-de Boor recurrence on the full vector otherwise.
#pragma once

#include <cstring>
#include <span>
#include <vector>

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

/// The u basis of one row's points for one surface (per point the first control point and
/// degree_u + 1 values), kept while the next row's u are the same numbers (a grid's rows under
/// the paper's or uniform rule): compared with memcmp, far cheaper than evaluating it again;
/// the same values either way, so the same bits. Used by the checks of every point.
class RowBasis {
 public:
  explicit RowBasis(const Surface& s) : s_(s), width_(static_cast<std::size_t>(s.degree_u) + 1) {}
  /// Makes the basis of the points at `u` (kept from the last row where `u` is the same).
  void of(std::span<const double> u) {
    if (u.size() == u_.size() &&
        (u.data() == u_.data() || std::memcmp(u.data(), u_.data(), u.size_bytes()) == 0))
      return;
    values_.resize(u.size() * width_);
    first_.resize(u.size());
    for (std::size_t k = 0; k < u.size(); ++k)
      first_[k] = basis_u(s_, u[k], values_.data() + k * width_);
    u_ = u;
  }
  int first(std::size_t k) const { return first_[k]; }
  const double* values(std::size_t k) const { return values_.data() + k * width_; }

 private:
  const Surface& s_;
  std::size_t width_;
  std::vector<double> values_;
  std::vector<int> first_;
  std::span<const double> u_;  // the u the kept basis is of
};

}  // namespace sfit
