#include "surface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sfit::test {

namespace {
double wrap_or_clamp(double t, double end, bool periodic) {
  if (periodic) {
    t = std::fmod(t, end);
    return t < 0 ? t + end : t;
  }
  return std::clamp(t, 0.0, end);
}

struct Grid {
  int gu = 0, gv = 0;
  std::vector<Point> p;
  explicit Grid(const Surface& s) {
    // At least 64 a way: a thin wing of one span across needs it to start on the right side.
    gu = std::max(64, 6 * (s.periodic_u ? s.count_u : s.count_u - s.degree_u));
    gv = std::max(64, 6 * (s.periodic_v ? s.count_v : s.count_v - s.degree_v));
    for (int a = 0; a <= gu; ++a)
      for (int b = 0; b <= gv; ++b) p.push_back(s.evaluate(s.u_end() * a / gu, s.v_end() * b / gv));
  }
};

double distance_from_grid(const Surface& s, const Grid& g, const Point& q) {
  double best = std::numeric_limits<double>::infinity();
  std::size_t at = 0;
  for (std::size_t i = 0; i < g.p.size(); ++i) {
    const double d = (g.p[i] - q).squaredNorm();
    if (d < best) best = d, at = i;
  }
  const double bu = s.u_end() * static_cast<double>(at / (g.gv + 1)) / g.gu;
  const double bv = s.v_end() * static_cast<double>(at % (g.gv + 1)) / g.gv;
  // Gauss-Newton on |S(u,v) - q|^2 from the nearest grid point, with step halving.
  double u = bu, v = bv;
  for (int it = 0; it < 30; ++it) {
    Point d[6];
    s.derivatives(u, v, d);
    const Point r = d[0] - q;
    const double a11 = d[1].dot(d[1]), a12 = d[1].dot(d[2]), a22 = d[2].dot(d[2]);
    const double g1 = d[1].dot(r), g2 = d[2].dot(r);
    const double det = a11 * a22 - a12 * a12;
    if (!(std::abs(det) > 1e-300)) break;
    double du = -(a22 * g1 - a12 * g2) / det, dv = -(a11 * g2 - a12 * g1) / det;
    const double now = r.squaredNorm();
    bool improved = false;
    for (int h = 0; h < 20; ++h) {
      const double nu = wrap_or_clamp(u + du, s.u_end(), s.periodic_u);
      const double nv = wrap_or_clamp(v + dv, s.v_end(), s.periodic_v);
      const double e = (s.evaluate(nu, nv) - q).squaredNorm();
      if (e < now) {
        u = nu, v = nv, best = std::min(best, e);
        improved = true;
        break;
      }
      du *= 0.5, dv *= 0.5;
    }
    if (!improved) break;
  }
  return std::sqrt(best);
}

}  // namespace

double distance_to_surface(const Surface& s, const Point& q) {
  return distance_from_grid(s, Grid(s), q);
}

std::vector<Point> samples_between_rows(const FitResult& fit, int per_span, int between) {
  const Surface& s = fit.surface;
  const int nu = per_span * (s.periodic_u ? s.count_u : s.count_u - s.degree_u);
  std::vector<double> vs;
  for (std::size_t j = 0; j + 1 < fit.v.size(); ++j)
    for (int k = 0; k < between; ++k)
      vs.push_back(fit.v[j] + (fit.v[j + 1] - fit.v[j]) * k / between);
  if (!fit.v.empty()) vs.push_back(fit.v.back());
  std::vector<Point> out;
  for (int a = 0; a <= nu; ++a)
    for (double v : vs) out.push_back(s.evaluate(s.u_end() * a / nu, v));
  return out;
}

double surface_gap(const FitResult& a, const FitResult& b) {
  double m = 0;
  const Grid ga(a.surface), gb(b.surface);
  for (const Point& p : samples_between_rows(a))
    m = std::max(m, distance_from_grid(b.surface, gb, p));
  for (const Point& p : samples_between_rows(b))
    m = std::max(m, distance_from_grid(a.surface, ga, p));
  return m;
}

}  // namespace sfit::test
