// B-spline basis functions on the uniform knot vectors of knots.h (docs/method.md section 2).
#pragma once

namespace sfit {

/// Largest degree sfit supports in either direction.
inline constexpr int kMaxDegree = 20;

/// Control-point index first + a reduced mod count, for 0 <= first < count and
/// 0 <= a <= degree < count (so one subtraction suffices; no integer division).
inline int wrap_index(int i, int count) {
  return i < count ? i : i - count;
}

/// eval_basis() for every case (the inline one below takes the commonest itself).
int eval_basis_general(int degree, int count, bool periodic, double t, double* values);

/// Evaluates the degree+1 basis functions that are non-zero at parameter t of a uniform curve
/// with `count` control points (Cox-de Boor, The NURBS Book algorithm A2.2).
/// Writes them to values[0 .. degree] and returns the index of the control point that
/// values[0] multiplies; value i multiplies control point first + i (reduce mod count when
/// periodic). t is clamped into the open domain and wrapped into the periodic one.
/// The commonest case inline (it runs per point per pass): an open bicubic curve, t in a span
/// away from the clamped ends, where the uniform closed form needs no knots; the same
/// arithmetic as eval_basis_general(), so the same bits.
inline int eval_basis(int degree, int count, bool periodic, double t, double* N) {
  if (degree == 3 && !periodic && t > 0 && t <= count - 3) {
    int f = static_cast<int>(t);
    if (f > count - 4) f = count - 4;
    if (f >= 2 && f <= count - 6) {
      const double x = t - f;
      const double u = 1.0 - x, x2 = x * x, u2 = u * u;
      constexpr double sixth = 1.0 / 6.0;
      N[0] = sixth * u2 * u;
      N[1] = sixth * (x2 * (3.0 * x - 6.0) + 4.0);
      N[2] = sixth * (u2 * (3.0 * u - 6.0) + 4.0);
      N[3] = sixth * x2 * x;
      return f;
    }
  }
  return eval_basis_general(degree, count, periodic, t, N);
}

/// Like eval_basis() with derivatives up to order `nderiv` (NURBS Book A2.3):
/// ders[k * (degree + 1) + i] is the k-th derivative of basis function first + i.
/// `ders` must hold (nderiv + 1) * (degree + 1) values.
int eval_basis_derivatives(int degree, int count, bool periodic, double t, int nderiv,
                           double* ders);

}  // namespace sfit
