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

/// Evaluates the degree+1 basis functions that are non-zero at parameter t of a uniform curve
/// with `count` control points (Cox-de Boor, The NURBS Book algorithm A2.2).
/// Writes them to values[0 .. degree] and returns the index of the control point that
/// values[0] multiplies; value i multiplies control point first + i (reduce mod count when
/// periodic). t is clamped into the open domain and wrapped into the periodic one.
int eval_basis(int degree, int count, bool periodic, double t, double* values);

/// Like eval_basis() with derivatives up to order `nderiv` (NURBS Book A2.3):
/// ders[k * (degree + 1) + i] is the k-th derivative of basis function first + i.
/// `ders` must hold (nderiv + 1) * (degree + 1) values.
int eval_basis_derivatives(int degree, int count, bool periodic, double t, int nderiv,
                           double* ders);

}  // namespace sfit
