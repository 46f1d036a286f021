#include "sfit/exchange/tessellate.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sfit/error.h"
#include "surface_frame.h"

namespace sfit::exchange {

namespace {

// Knot spans of a uniform direction: count - degree (open) or count (periodic).
int spans(int degree, int count, bool periodic) {
  return periodic ? count : count - degree;
}

std::vector<double> sample_parameters(double end, int n, bool periodic) {
  std::vector<double> t(static_cast<std::size_t>(n));
  for (int a = 0; a < n; ++a)
    t[static_cast<std::size_t>(a)] =
        periodic ? end * a / n : (a == n - 1 ? end : end * a / (n - 1));
  return t;
}

// Whether the surface closes on itself along u (along v with `along_v`): periodic, or clamped
// with its first and last control-point columns (rows) equal, as closed corner knots write a
// crease at the seam (docs/method.md 7.13). The mesh then wraps there: one seam, no boundary.
bool wraps(const Surface& s, bool along_v) {
  if (along_v ? s.periodic_v : s.periodic_u) return true;
  const int nu = s.count_u, nv = s.count_v;
  if (nu < 2 || nv < 2 || s.control.size() != static_cast<std::size_t>(nu) * nv) return false;
  for (int k = 0; k < (along_v ? nu : nv); ++k) {
    const std::size_t first = along_v ? static_cast<std::size_t>(k) * nv : k;
    const std::size_t last = along_v ? first + nv - 1 : static_cast<std::size_t>(nu - 1) * nv + k;
    if (s.control[first] != s.control[last]) return false;
  }
  return true;
}

[[noreturn]] void bad_density(const std::string& what, int n) {
  throw Error(ErrorCode::kUsage, what, Place{.option = "--mesh-density"}, {static_cast<double>(n)});
}

}  // namespace

double default_chord(const Surface& surface, double tolerance) {
  if (tolerance > 0) return tolerance / 4;
  const detail::SurfaceFrame f(surface);
  Point lo = Point::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Point& p : f.scaled.control) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diagonal = f.scaled.control.empty() ? 0.0 : (hi - lo).norm() * f.size;
  return diagonal > 0 ? 2.5e-4 * diagonal : 1.0;
}

Density choose_density(const Surface& s, double chord_in, int max_samples, double max_triangles) {
  const detail::SurfaceFrame f(s);
  const double chord = chord_in / f.size;  // in the scaled coordinates
  const int su = spans(s.degree_u, s.count_u, s.periodic_u);
  const int sv = spans(s.degree_v, s.count_v, s.periodic_v);
  // Maxima of the second derivatives, 4 samples per knot span and at the span ends.
  double muu = 0, muv = 0, mvv = 0;
  const int nu = 4 * su + 1, nv = 4 * sv + 1;
  for (int b = 0; b < nv; ++b) {
    const double v = s.v_end() * b / (nv - 1);
    for (int a = 0; a < nu; ++a) {
      Point d[6];
      f.derivatives(s.u_end() * a / (nu - 1), v, d);
      muu = std::max(muu, d[3].norm());
      muv = std::max(muv, d[4].norm());
      mvv = std::max(mvv, d[5].norm());
    }
  }
  // h_u^2 M_uu = h_v^2 M_vv = a^2 and (2 a^2 + 2 h_u h_v M_uv) / 8 = chord.
  const double r = (muu > 0 && mvv > 0) ? muv / std::sqrt(muu * mvv) : 0.0;
  double hu = 0, hv = 0;
  if (muu > 0 && mvv > 0) {
    const double a2 = 8 * chord / (2 + 2 * r);
    hu = std::sqrt(a2 / muu);
    hv = std::sqrt(a2 / mvv);
  } else if (muu > 0) {  // straight along v: the twist term alone limits h_v
    hu = std::sqrt(4 * chord / muu);
    hv = muv > 0 ? 4 * chord / (hu * muv) : s.v_end();
  } else if (mvv > 0) {
    hv = std::sqrt(4 * chord / mvv);
    hu = muv > 0 ? 4 * chord / (hv * muv) : s.u_end();
  } else {  // bilinear in both: only the twist term
    hu = hv = muv > 0 ? std::sqrt(4 * chord / muv) : std::max(s.u_end(), s.v_end());
  }
  auto cells = [&](double end, double h, int span_count, double per_span) {
    return std::max(std::ceil(end / h - 1e-9), per_span * span_count);
  };
  double cu = cells(s.u_end(), hu, su, 4), cv = cells(s.v_end(), hv, sv, 4);
  if (max_triangles > 0 && 2 * cu * cv > max_triangles) {
    // Coarsen both directions by one factor; at least one cell per knot span.
    const double k = std::sqrt(2 * cu * cv / max_triangles);
    cu = std::max(std::floor(cu / k), 1.0 * su);
    cv = std::max(std::floor(cv / k), 1.0 * sv);
  }
  auto count = [&](double c, bool periodic) {
    const double n = c + (periodic ? 0 : 1);
    return static_cast<int>(std::min(n, static_cast<double>(max_samples)));
  };
  Density d;
  const bool wu = wraps(s, false), wv = wraps(s, true);
  d.samples_u = count(cu, wu);
  d.samples_v = count(cv, wv);
  const double hu2 = s.u_end() / (wu ? d.samples_u : d.samples_u - 1);
  const double hv2 = s.v_end() / (wv ? d.samples_v : d.samples_v - 1);
  d.bound = (hu2 * hu2 * muu + 2 * hu2 * hv2 * muv + hv2 * hv2 * mvv) / 8 * f.size;
  return d;
}

Mesh tessellate(const Surface& s, int samples_u, int samples_v) {
  auto check = [](int n, bool periodic, const char* dir) {
    const int least = periodic ? 3 : 2;
    if (n < least || n > 100000)
      bad_density(std::string("mesh density along ") + dir + " must be " + std::to_string(least) +
                      " ... 100000 samples, got " + std::to_string(n),
                  n);
  };
  const bool wu = wraps(s, false), wv = wraps(s, true);
  check(samples_u, wu, "u");
  check(samples_v, wv, "v");
  if (static_cast<double>(samples_u) * samples_v > 5e7)
    throw Error(ErrorCode::kUsage,
                "mesh of " + std::to_string(samples_u) + " x " + std::to_string(samples_v) +
                    " samples is too large (at most 5e7 vertices)",
                Place{.option = "--mesh-density"});
  const detail::SurfaceFrame f(s);
  Mesh m;
  m.samples_u = samples_u;
  m.samples_v = samples_v;
  m.periodic_u = wu;
  m.periodic_v = wv;
  m.u = sample_parameters(s.u_end(), samples_u, wu);
  m.v = sample_parameters(s.v_end(), samples_v, wv);
  const std::size_t n = static_cast<std::size_t>(samples_u) * samples_v;
  m.vertices.resize(n);
  m.normals.resize(n);
  std::vector<char> analytic(n, 0);
  for (int b = 0; b < samples_v; ++b)
    for (int a = 0; a < samples_u; ++a) {
      const std::size_t k = m.index(a, b);
      m.vertices[k] = s.evaluate(m.u[a], m.v[b]);
      Point d[6];
      f.derivatives(m.u[a], m.v[b], d);
      analytic[k] = detail::SurfaceFrame::unit_normal(d, m.normals[k]);
    }
  m.triangles.reserve(static_cast<std::size_t>(m.quads_u()) * m.quads_v() * 2);
  for (int b = 0; b < m.quads_v(); ++b)
    for (int a = 0; a < m.quads_u(); ++a) {
      const std::uint32_t p = m.index(a, b), q = m.index(a + 1, b), r = m.index(a + 1, b + 1),
                          t = m.index(a, b + 1);
      m.triangles.push_back({p, q, r});
      m.triangles.push_back({p, r, t});
    }
  if (std::find(analytic.begin(), analytic.end(), 0) == analytic.end()) return m;
  // Degenerate points (poles): the normal beside each, then one mean normal for a whole
  // collapsed row or column; the triangle normals around it (scaled) as the last resort.
  std::vector<char> found(n, 0);
  for (int b = 0; b < samples_v; ++b)
    for (int a = 0; a < samples_u; ++a) {
      const std::size_t k = m.index(a, b);
      if (!analytic[k]) found[k] = f.normal_near(m.u[a], m.v[b], m.normals[k]);
    }
  auto pool = [&](int count, auto&& index_of) {  // one normal for a fully degenerate line
    Point sum = Point::Zero();
    for (int i = 0; i < count; ++i) {
      const std::size_t k = index_of(i);
      if (analytic[k]) return;
      if (found[k]) sum += m.normals[k];
    }
    if (!(sum.norm() > 1e-8)) return;
    for (int i = 0; i < count; ++i) {
      m.normals[index_of(i)] = sum.normalized();
      found[index_of(i)] = 1;
    }
  };
  for (int b = 0; b < samples_v; ++b) pool(samples_u, [&](int a) { return m.index(a, b); });
  for (int a = 0; a < samples_u; ++a) pool(samples_v, [&](int b) { return m.index(a, b); });
  std::vector<Point> sum(n, Point::Zero());
  for (const auto& tri : m.triangles) {
    const Point p0 = (m.vertices[tri[0]] - f.centre) / f.size;
    const Point e = ((m.vertices[tri[1]] - f.centre) / f.size - p0)
                        .cross((m.vertices[tri[2]] - f.centre) / f.size - p0);
    for (auto k : tri) sum[k] += e;
  }
  for (std::size_t k = 0; k < n; ++k)
    if (!analytic[k] && !found[k])
      m.normals[k] = sum[k].norm() > 0 ? Point(sum[k].normalized()) : Point(0, 0, 1);
  return m;
}

Curvature curvature(const Surface& s, double u, double v) {
  return detail::SurfaceFrame(s).curvature(u, v);
}

}  // namespace sfit::exchange
