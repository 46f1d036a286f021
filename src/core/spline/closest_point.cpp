#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "sfit/surface_eval.h"

namespace sfit {
namespace {

std::vector<double> sample_parameters(int degree, int count, bool periodic, double end) {
  const int spans = periodic ? count : count - degree;
  const int n = std::clamp(4 * spans + (periodic ? 0 : 1), 8, 256);
  std::vector<double> t(static_cast<std::size_t>(n));
  // A periodic direction: n samples of [0, end) (end is the start again); open: [0, end].
  const double step = end / (periodic ? n : n - 1);
  for (int k = 0; k < n; ++k) t[k] = k * step;
  if (!periodic) t.back() = end;
  return t;
}

// (u, v) into the domain: clamped in an open direction, wrapped around a periodic one.
double into(double t, double end, bool periodic) {
  if (periodic) {
    t = std::fmod(t, end);
    if (t < 0) t += end;
    return t >= end ? 0.0 : t;
  }
  return std::clamp(t, 0.0, end);
}

}  // namespace

ClosestPointFinder::ClosestPointFinder(const Surface& surface) : surface_(surface) {
  const Surface& s = surface_;
  su_ = sample_parameters(s.degree_u, s.count_u, s.periodic_u, s.u_end());
  sv_ = sample_parameters(s.degree_v, s.count_v, s.periodic_v, s.v_end());
  const DirectionBasis bu = direction_basis(s, true, su_, 0);
  const DirectionBasis bv = direction_basis(s, false, sv_, 0);
  samples_.resize(su_.size() * sv_.size());
  for (std::size_t a = 0; a < su_.size(); ++a)
    for (std::size_t b = 0; b < sv_.size(); ++b)
      surface_derivatives(s, bu, a, bv, b, &samples_[a * sv_.size() + b]);
}

namespace {

// |grad| of 0.5 |S - p|^2 in the free directions (a variable held at a bound whose descent
// points outward does not count).
double gradient_norm(const Surface& s, const Point d[6], const Point& p, double u, double v) {
  const Point r = d[0] - p;
  double gu = r.dot(d[1]), gv = r.dot(d[2]);
  if (!s.periodic_u && ((u <= 0 && gu > 0) || (u >= s.u_end() && gu < 0))) gu = 0;
  if (!s.periodic_v && ((v <= 0 && gv > 0) || (v >= s.v_end() && gv < 0))) gv = 0;
  return std::hypot(gu, gv);
}

// Newton's method on f = |S(u, v) - p|^2 from (u, v), projected onto the domain.
ClosestPoint descend(const Surface& s, const Point& p, double u, double v) {
  const double ue = s.u_end(), ve = s.v_end();
  Point d[6];
  surface_derivatives(s, u, v, 2, d);
  double f = (d[0] - p).squaredNorm();
  double gn = gradient_norm(s, d, p, u, v);
  for (int iter = 0; iter < 100 && gn > 0; ++iter) {
    const Point r = d[0] - p;
    const double g[2] = {r.dot(d[1]), r.dot(d[2])};
    double H[2][2] = {{d[1].dot(d[1]) + r.dot(d[3]), d[1].dot(d[2]) + r.dot(d[4])},
                      {0, d[2].dot(d[2]) + r.dot(d[5])}};
    H[1][0] = H[0][1];
    // Bound constraints of an open direction: a variable at its bound whose descent points
    // out of the domain is held there; Newton runs on the others.
    bool fixed[2] = {false, false};
    if (!s.periodic_u) fixed[0] = (u <= 0 && g[0] > 0) || (u >= ue && g[0] < 0);
    if (!s.periodic_v) fixed[1] = (v <= 0 && g[1] > 0) || (v >= ve && g[1] < 0);
    double step[2] = {0, 0};
    if (!fixed[0] && !fixed[1]) {
      const double det = H[0][0] * H[1][1] - H[0][1] * H[0][1];
      if (H[0][0] > 0 && det > 0) {
        step[0] = -(H[1][1] * g[0] - H[0][1] * g[1]) / det;
        step[1] = -(H[0][0] * g[1] - H[0][1] * g[0]) / det;
      } else {  // not convex here: steepest descent, scaled by the metric
        const double scale = d[1].squaredNorm() + d[2].squaredNorm();
        if (!(scale > 0)) break;
        step[0] = -g[0] / scale;
        step[1] = -g[1] / scale;
      }
    } else {
      for (int k = 0; k < 2; ++k) {
        if (fixed[k]) continue;
        const double h = H[k][k] > 0 ? H[k][k] : d[1 + k].squaredNorm();
        if (h > 0) step[k] = -g[k] / h;
      }
    }
    // Line search: the first of t = 1, 1/2, 1/4, ... that lowers the distance, or, where the
    // distance is flat to round-off (at the minimum), lowers the gradient.
    const double flat = 1e-15 * (p.squaredNorm() + d[0].squaredNorm() + f);
    bool moved = false;
    Point dn[6];
    double t = 1;
    for (int half = 0; half < 40; ++half, t *= 0.5) {
      const double un = into(u + t * step[0], ue, s.periodic_u);
      const double vn = into(v + t * step[1], ve, s.periodic_v);
      if (un == u && vn == v) break;
      surface_derivatives(s, un, vn, 2, dn);
      const double fn = (dn[0] - p).squaredNorm();
      const double gnn = fn <= f + flat ? gradient_norm(s, dn, p, un, vn) : gn;
      if (fn < f || gnn < gn) {
        u = un;
        v = vn;
        f = fn;
        gn = gnn < gn ? gnn : gradient_norm(s, dn, p, un, vn);
        std::copy(dn, dn + 6, d);
        moved = true;
        break;
      }
    }
    if (!moved) break;
  }
  return {u, v, d[0], std::sqrt(f)};
}

}  // namespace

ClosestPoint ClosestPointFinder::find(const Point& p) const {
  // Newton from each of the nearest samples (a few: the nearest alone can sit in the basin
  // of a farther local minimum on a wavy surface); the nearest result wins.
  constexpr std::size_t kStarts = 4;
  std::array<std::size_t, kStarts> best;
  std::array<double, kStarts> best_d2;
  best.fill(0);
  best_d2.fill(std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < samples_.size(); ++k) {
    const double d2 = (samples_[k] - p).squaredNorm();
    if (!(d2 < best_d2[kStarts - 1])) continue;
    std::size_t at = kStarts - 1;
    while (at > 0 && d2 < best_d2[at - 1]) {
      best_d2[at] = best_d2[at - 1];
      best[at] = best[at - 1];
      --at;
    }
    best_d2[at] = d2;
    best[at] = k;
  }
  ClosestPoint out;
  out.distance = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < kStarts && k < samples_.size(); ++k) {
    const ClosestPoint c =
        descend(surface_, p, su_[best[k] / sv_.size()], sv_[best[k] % sv_.size()]);
    if (c.distance < out.distance) out = c;
  }
  return out;
}

}  // namespace sfit
