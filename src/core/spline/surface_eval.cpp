#include "sfit/surface_eval.h"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "basis_knots.h"
#include "sfit/error.h"

namespace sfit {
namespace {

constexpr int M = kMaxDegree + 1;

void check_order(int order) {
  if (order < 0 || order > 2)
    throw Error(ErrorCode::kUsage,
                "derivatives of order 0, 1 or 2 only, got " + std::to_string(order),
                Place{.option = "order"}, {static_cast<double>(order)});
}

// Sum over the (degree_u + 1) x (degree_v + 1) control points the bases touch. The order of
// the sums is that of Surface::evaluate() and Surface::derivatives(), so out[0] is evaluate().
void combine(const Surface& s, int order, int fu, const double* du, int fv, const double* dv,
             Point* out) {
  const int pu = s.degree_u, pv = s.degree_v;
  const int n = derivative_count(order);
  for (int k = 0; k < n; ++k) out[k] = Point::Zero();
  for (int a = 0; a <= pu; ++a) {
    const int i = wrap_index(fu + a, s.count_u);
    Point c0 = Point::Zero(), c1 = Point::Zero(), c2 = Point::Zero();
    if (order == 0) {
      for (int b = 0; b <= pv; ++b) c0 += dv[b] * s.at(i, wrap_index(fv + b, s.count_v));
      out[0] += du[a] * c0;
      continue;
    }
    for (int b = 0; b <= pv; ++b) {
      const Point& P = s.at(i, wrap_index(fv + b, s.count_v));
      c0 += dv[b] * P;
      c1 += dv[(pv + 1) + b] * P;
      if (order == 2) c2 += dv[2 * (pv + 1) + b] * P;
    }
    const double n0 = du[a], n1 = du[(pu + 1) + a];
    out[0] += n0 * c0;
    out[1] += n1 * c0;
    out[2] += n0 * c1;
    if (order == 2) {
      out[3] += du[2 * (pu + 1) + a] * c0;
      out[4] += n1 * c1;
      out[5] += n0 * c2;
    }
  }
}

// sum_a Nu[a] (sum_b Nv[b] P_ab): the order of sums of combine() for one output.
Point combine_one(const Surface& s, int fu, const double* nu, int fv, const double* nv) {
  Point out = Point::Zero();
  for (int a = 0; a <= s.degree_u; ++a) {
    const int i = wrap_index(fu + a, s.count_u);
    Point c = Point::Zero();
    for (int b = 0; b <= s.degree_v; ++b) c += nv[b] * s.at(i, wrap_index(fv + b, s.count_v));
    out += nu[a] * c;
  }
  return out;
}

void check_partial(int du, int dv) {
  if (du < 0 || dv < 0 || du + dv > 2)
    throw Error(ErrorCode::kUsage,
                "derivatives of order du + dv <= 2 (du, dv >= 0), got du=" + std::to_string(du) +
                    ", dv=" + std::to_string(dv),
                Place{.option = du < 0 || du + dv > 2 ? "du" : "dv"},
                {static_cast<double>(du), static_cast<double>(dv)});
}

}  // namespace

Point surface_partial(const Surface& s, double u, double v, int du, int dv) {
  check_partial(du, dv);
  std::array<double, 3 * M> bu, bv;
  const int fu = eval_basis_upto(s.knots_u, s.degree_u, s.count_u, s.periodic_u, u, du, bu.data());
  const int fv = eval_basis_upto(s.knots_v, s.degree_v, s.count_v, s.periodic_v, v, dv, bv.data());
  return combine_one(s, fu, bu.data() + du * (s.degree_u + 1), fv,
                     bv.data() + dv * (s.degree_v + 1));
}

Point surface_partial(const Surface& s, const DirectionBasis& u, std::size_t i,
                      const DirectionBasis& v, std::size_t j, int du, int dv) {
  check_partial(du, dv);
  const std::size_t su = static_cast<std::size_t>(u.order + 1) * (u.degree + 1);
  const std::size_t sv = static_cast<std::size_t>(v.order + 1) * (v.degree + 1);
  return combine_one(s, u.first[i], u.d.data() + i * su + du * (u.degree + 1), v.first[j],
                     v.d.data() + j * sv + dv * (v.degree + 1));
}

void surface_derivatives(const Surface& s, double u, double v, int order, Point* out) {
  check_order(order);
  std::array<double, 3 * M> du, dv;
  const int fu =
      eval_basis_upto(s.knots_u, s.degree_u, s.count_u, s.periodic_u, u, order, du.data());
  const int fv =
      eval_basis_upto(s.knots_v, s.degree_v, s.count_v, s.periodic_v, v, order, dv.data());
  combine(s, order, fu, du.data(), fv, dv.data(), out);
}

DirectionBasis direction_basis(const Surface& s, bool along_u, std::span<const double> t,
                               int order) {
  check_order(order);
  DirectionBasis b;
  b.degree = along_u ? s.degree_u : s.degree_v;
  b.order = order;
  const int count = along_u ? s.count_u : s.count_v;
  const bool periodic = along_u ? s.periodic_u : s.periodic_v;
  const KnotVector& knots = along_u ? s.knots_u : s.knots_v;
  const std::size_t stride = static_cast<std::size_t>(order + 1) * (b.degree + 1);
  b.first.resize(t.size());
  b.d.resize(t.size() * stride);
  std::array<double, 3 * M> d;
  for (std::size_t k = 0; k < t.size(); ++k) {
    b.first[k] = eval_basis_upto(knots, b.degree, count, periodic, t[k], order, d.data());
    std::copy(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(stride),
              b.d.begin() + static_cast<std::ptrdiff_t>(k * stride));
  }
  return b;
}

void surface_derivatives(const Surface& s, const DirectionBasis& u, std::size_t i,
                         const DirectionBasis& v, std::size_t j, Point* out) {
  const std::size_t su = static_cast<std::size_t>(u.order + 1) * (u.degree + 1);
  const std::size_t sv = static_cast<std::size_t>(v.order + 1) * (v.degree + 1);
  combine(s, u.order, u.first[i], u.d.data() + i * su, v.first[j], v.d.data() + j * sv, out);
}

Curvature curvature_from(const Point d[6]) {
  const Point& su = d[1];
  const Point& sv = d[2];
  const Point cross = su.cross(sv);
  const double len = cross.norm();
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(len > 0) || !std::isfinite(len)) return {nan, nan, nan, nan};
  const Point n = cross / len;
  const double E = su.dot(su), F = su.dot(sv), G = sv.dot(sv);
  const double L = d[3].dot(n), Mm = d[4].dot(n), N = d[5].dot(n);
  const double det = E * G - F * F;  // = len^2 up to round-off
  Curvature c;
  c.gaussian = (L * N - Mm * Mm) / det;
  c.mean = (E * N - 2 * F * Mm + G * L) / (2 * det);
  const double disc = std::sqrt(std::max(0.0, c.mean * c.mean - c.gaussian));
  c.k1 = c.mean + disc;
  c.k2 = c.mean - disc;
  return c;
}

Curvature surface_curvature(const Surface& s, double u, double v) {
  Point d[6];
  surface_derivatives(s, u, v, 2, d);
  return curvature_from(d);
}

}  // namespace sfit
