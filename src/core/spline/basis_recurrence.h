// The Cox-de Boor recurrences (The NURBS Book A2.2 and A2.3) on any knots, given as a functor
// knot(m) of the full-vector index m: shared by the uniform knots of basis.cpp and the
// non-uniform ones of basis_knots.cpp (the same arithmetic, so the same bits).
#pragma once

#include <algorithm>
#include <array>

#include "basis.h"

namespace sfit::detail {

/// The degree + 1 non-zero basis functions on span s at t (A2.2) into N[0 .. degree].
template <class Knot>
void basis_values(const Knot& knot, int degree, int s, double t, double* N) {
  std::array<double, kMaxDegree + 1> left{}, right{};
  N[0] = 1.0;
  for (int j = 1; j <= degree; ++j) {
    left[j] = t - knot(s + 1 - j);
    right[j] = knot(s + j) - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
}

/// The basis functions and their derivatives up to nderiv on span s at t (A2.3):
/// ders[k * (degree + 1) + i]; ders[0 .. degree] equal basis_values() bit for bit.
template <class Knot>
void basis_derivatives(const Knot& knot, int degree, int s, double t, int nderiv, double* ders) {
  const int p = degree;
  constexpr int M = kMaxDegree + 1;
  double ndu[M][M];
  double a[2][M];
  std::array<double, M> left{}, right{};
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knot(s + 1 - j);
    right[j] = knot(s + j) - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int j = 0; j <= p; ++j) ders[j] = ndu[j][p];
  for (int k = 1; k <= nderiv; ++k)
    for (int j = 0; j <= p; ++j) ders[k * (p + 1) + j] = 0.0;
  const int n = std::min(nderiv, p);
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= n; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = (rk >= -1) ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k * (p + 1) + r] = d;
      std::swap(s1, s2);
    }
  }
  double f = p;
  for (int k = 1; k <= n; ++k) {
    for (int j = 0; j <= p; ++j) ders[k * (p + 1) + j] *= f;
    f *= (p - k);
  }
}

}  // namespace sfit::detail
