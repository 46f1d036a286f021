#include "basis.h"
#include "basis_recurrence.h"
#include "basis_upto.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sfit {
namespace {

// Local knots around span s: knot(m) for m in [s - degree + 1, s + degree].
struct LocalKnots {
  int degree, count;
  bool periodic;
  double knot(int m) const {
    if (periodic) return m - degree;
    return std::clamp(m - degree, 0, count - degree);
  }
};

// Returns the span index s (full knot vector indexing) and the reduced parameter.
int find_span(int degree, int count, bool periodic, double& t) {
  // t >= 0 here, so the int conversion is floor() without a library call (this runs once per
  // point per solve).
  if (periodic) {
    if (!(t >= 0 && t < count)) {  // wrap only when needed: fmod is a library call
      t = std::fmod(t, static_cast<double>(count));
      if (t < 0) t += count;
      if (!(t >= 0)) t = 0;  // NaN
    }
    int f = static_cast<int>(t);
    if (f >= count) {  // round-off at the seam
      f = 0;
      t = 0;
    }
    return degree + f;
  }
  const double end = count - degree;
  if (!(t > 0)) t = 0;  // also maps NaN to 0
  if (t > end) t = end;
  int f = static_cast<int>(t);
  if (f > count - degree - 1) f = count - degree - 1;
  return degree + f;
}

}  // namespace

namespace {
// 1/j, so the uniform recurrence below multiplies instead of dividing.
constexpr auto kInverse = [] {
  std::array<double, kMaxDegree + 1> inv{};
  for (int j = 1; j <= kMaxDegree; ++j) inv[j] = 1.0 / j;
  return inv;
}();
}  // namespace

int eval_basis_general(int degree, int count, bool periodic, double t, double* N) {
  const int s = find_span(degree, count, periodic, t);
  // Where the 2*degree knots around the span are consecutive integers (always for periodic,
  // away from the clamped ends otherwise), left[j] = x + j - 1 and right[j] = j - x with
  // x = t - knot(s), and every denominator of A2.2 equals j: no division needed.
  if (periodic || (s >= 2 * degree - 1 && s <= count - degree)) {
    const double x = t - (s - degree);
    // Closed forms of the uniform B-spline for the common degrees (a fifth of the cost).
    switch (degree) {
      case 1:
        N[0] = 1.0 - x;
        N[1] = x;
        return s - degree;
      case 2: {
        const double u = 1.0 - x;
        N[0] = 0.5 * u * u;
        N[1] = 0.5 + x * u;
        N[2] = 0.5 * x * x;
        return s - degree;
      }
      case 3: {
        const double u = 1.0 - x, x2 = x * x, u2 = u * u;
        constexpr double sixth = 1.0 / 6.0;
        N[0] = sixth * u2 * u;
        N[1] = sixth * (x2 * (3.0 * x - 6.0) + 4.0);
        N[2] = sixth * (u2 * (3.0 * u - 6.0) + 4.0);  // the mirror image of N[1]
        N[3] = sixth * x2 * x;
        return s - degree;
      }
      default:
        break;
    }
    N[0] = 1.0;
    for (int j = 1; j <= degree; ++j) {
      double saved = 0.0;
      const double inv = kInverse[j];
      for (int r = 0; r < j; ++r) {
        const double temp = N[r] * inv;
        N[r] = saved + (r + 1 - x) * temp;
        saved = (x + j - r - 1) * temp;
      }
      N[j] = saved;
    }
    return s - degree;
  }
  const LocalKnots U{degree, count, periodic};
  detail::basis_values([&U](int m) { return U.knot(m); }, degree, s, t, N);
  return s - degree;
}

int eval_basis_derivatives(int degree, int count, bool periodic, double t, int nderiv,
                           double* ders) {
  const int p = degree;
  const int s = find_span(p, count, periodic, t);
  const LocalKnots U{p, count, periodic};
  detail::basis_derivatives([&U](int m) { return U.knot(m); }, p, s, t, nderiv, ders);
  return s - p;
}

int eval_basis_upto(int degree, int count, bool periodic, double t, int nderiv, double* ders) {
  const int p = degree;
  if (nderiv > 2) return eval_basis_derivatives(p, count, periodic, t, nderiv, ders);
  const int first = eval_basis(p, count, periodic, t, ders);
  if (nderiv <= 0) return first;
  double reduced = t;
  const int s = find_span(p, count, periodic, reduced);
  const bool uniform = periodic || (s >= 2 * p - 1 && s <= count - p);
  // The basis of degrees p - 2 (r) and p - 1 (q) on the same span, by the recurrence of
  // eval_basis(): division-free on uniform spans, A2.2 with the local knots elsewhere.
  std::array<double, kMaxDegree + 1> N{}, q{}, r{};
  N[0] = 1.0;
  if (p - 1 == 0) q[0] = 1.0;
  if (p - 2 == 0) r[0] = 1.0;
  const LocalKnots U{p, count, periodic};
  const double x = reduced - (s - p);
  std::array<double, kMaxDegree + 1> left{}, right{};
  for (int j = 1; j <= p - 1; ++j) {
    double saved = 0.0;
    if (uniform) {
      const double inv = kInverse[j];
      for (int i = 0; i < j; ++i) {
        const double temp = N[i] * inv;
        N[i] = saved + (i + 1 - x) * temp;
        saved = (x + j - i - 1) * temp;
      }
    } else {
      left[j] = reduced - U.knot(s + 1 - j);
      right[j] = U.knot(s + j) - reduced;
      for (int i = 0; i < j; ++i) {
        const double temp = N[i] / (right[i + 1] + left[j - i]);
        N[i] = saved + right[i + 1] * temp;
        saved = left[j - i] * temp;
      }
    }
    N[j] = saved;
    if (j == p - 2) r = N;
    if (j == p - 1) q = N;
  }
  double* d1 = ders + (p + 1);
  double* d2 = ders + 2 * (p + 1);
  if (uniform) {
    // Unit spacing: N_{s-p+a,p}' = q[a-1] - q[a] (q has p entries); N'' = r[a-2] - 2 r[a-1]
    // + r[a] (r has p - 1).
    for (int a = 0; a <= p; ++a) d1[a] = (a > 0 ? q[a - 1] : 0.0) - (a < p ? q[a] : 0.0);
    if (nderiv >= 2)
      for (int a = 0; a <= p; ++a) {
        if (p < 2) {
          d2[a] = 0.0;
          continue;
        }
        const double r2 = a >= 2 ? r[a - 2] : 0.0;
        const double r1 = (a >= 1 && a - 1 <= p - 2) ? r[a - 1] : 0.0;
        const double r0 = a <= p - 2 ? r[a] : 0.0;
        d2[a] = r2 - 2.0 * r1 + r0;
      }
    return first;
  }
  // N'_{i,k} = k / (u_{i+k} - u_i) N_{i,k-1} - k / (u_{i+k+1} - u_{i+1}) N_{i+1,k-1}, a term
  // dropped where its knot interval is empty (its N is zero there).
  auto term = [](double k, double value, double width) {
    return width > 0 ? k * value / width : 0.0;
  };
  for (int a = 0; a <= p; ++a)
    d1[a] = (a > 0 ? term(p, q[a - 1], U.knot(s + a) - U.knot(s - p + a)) : 0.0) -
            (a < p ? term(p, q[a], U.knot(s + a + 1) - U.knot(s - p + a + 1)) : 0.0);
  if (nderiv >= 2) {
    // Derivatives of the degree p - 1 functions N_{s-p+1+b, p-1} from r, then as above.
    std::array<double, kMaxDegree + 1> dq{};
    for (int b = 0; b < p; ++b)
      dq[b] = p < 2 ? 0.0
                    : (b > 0 ? term(p - 1, r[b - 1], U.knot(s + b) - U.knot(s - p + 1 + b)) : 0.0) -
                          (b < p - 1 ? term(p - 1, r[b], U.knot(s + b + 1) - U.knot(s - p + 2 + b))
                                     : 0.0);
    for (int a = 0; a <= p; ++a)
      d2[a] = (a > 0 ? term(p, dq[a - 1], U.knot(s + a) - U.knot(s - p + a)) : 0.0) -
              (a < p ? term(p, dq[a], U.knot(s + a + 1) - U.knot(s - p + a + 1)) : 0.0);
  }
  return first;
}

}  // namespace sfit
