#include "sfit/exchange/tessellate.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sfit/error.h"

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

}  // namespace

double default_chord(const Surface& surface, double tolerance) {
  if (tolerance > 0) return tolerance / 4;
  Point lo = Point::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Point& p : surface.control) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diagonal = surface.control.empty() ? 0.0 : (hi - lo).norm();
  return diagonal > 0 ? 2.5e-4 * diagonal : 1.0;
}

Density choose_density(const Surface& s, double chord, int max_samples) {
  const int su = spans(s.degree_u, s.count_u, s.periodic_u);
  const int sv = spans(s.degree_v, s.count_v, s.periodic_v);
  // Maxima of the second derivatives, 8 samples per knot span and at the span ends.
  double muu = 0, muv = 0, mvv = 0;
  const int nu = 8 * su + 1, nv = 8 * sv + 1;
  for (int b = 0; b < nv; ++b) {
    const double v = s.v_end() * b / (nv - 1);
    for (int a = 0; a < nu; ++a) {
      Point d[6];
      s.derivatives(s.u_end() * a / (nu - 1), v, d);
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
  auto count = [&](double end, double h, int span_count, bool periodic) {
    const double cells = std::ceil(end / h - 1e-9);
    const double minimum = 4.0 * span_count;
    double n = std::max(cells, minimum) + (periodic ? 0 : 1);
    n = std::min(n, static_cast<double>(max_samples));
    return static_cast<int>(n);
  };
  Density d;
  d.samples_u = count(s.u_end(), hu, su, s.periodic_u);
  d.samples_v = count(s.v_end(), hv, sv, s.periodic_v);
  const double cu = s.u_end() / (s.periodic_u ? d.samples_u : d.samples_u - 1);
  const double cv = s.v_end() / (s.periodic_v ? d.samples_v : d.samples_v - 1);
  d.bound = (cu * cu * muu + 2 * cu * cv * muv + cv * cv * mvv) / 8;
  return d;
}

Mesh tessellate(const Surface& s, int samples_u, int samples_v) {
  auto check = [](int n, bool periodic, const char* dir) {
    const int least = periodic ? 3 : 2;
    if (n < least || n > 100000)
      throw Error(ErrorCode::kUsage,
                  std::string("mesh density along ") + dir + " must be " + std::to_string(least) +
                      " ... 100000 samples, got " + std::to_string(n),
                  Place{.option = "--mesh-density"}, {static_cast<double>(n)});
  };
  check(samples_u, s.periodic_u, "u");
  check(samples_v, s.periodic_v, "v");
  if (static_cast<double>(samples_u) * samples_v > 5e7)
    throw Error(ErrorCode::kUsage,
                "mesh of " + std::to_string(samples_u) + " x " + std::to_string(samples_v) +
                    " samples is too large (at most 5e7 vertices)",
                Place{.option = "--mesh-density"});
  Mesh m;
  m.samples_u = samples_u;
  m.samples_v = samples_v;
  m.periodic_u = s.periodic_u;
  m.periodic_v = s.periodic_v;
  m.u = sample_parameters(s.u_end(), samples_u, s.periodic_u);
  m.v = sample_parameters(s.v_end(), samples_v, s.periodic_v);
  const std::size_t n = static_cast<std::size_t>(samples_u) * samples_v;
  m.vertices.resize(n);
  m.normals.resize(n);
  std::vector<bool> analytic(n, false);
  // A normal counts as analytic when |S_u x S_v| is not negligible against |S_u| |S_v| and the
  // size of the parameter cell.
  for (int b = 0; b < samples_v; ++b)
    for (int a = 0; a < samples_u; ++a) {
      Point d[6];
      s.derivatives(m.u[a], m.v[b], d);
      const std::size_t k = m.index(a, b);
      m.vertices[k] = d[0];
      const Point c = d[1].cross(d[2]);
      const double scale = d[1].norm() * d[2].norm();
      if (scale > 0 && c.norm() > 1e-8 * scale) {
        m.normals[k] = c.normalized();
        analytic[k] = true;
      }
    }
  m.triangles.reserve(static_cast<std::size_t>(m.quads_u()) * m.quads_v() * 2);
  for (int b = 0; b < m.quads_v(); ++b)
    for (int a = 0; a < m.quads_u(); ++a) {
      const std::uint32_t p = m.index(a, b), q = m.index(a + 1, b), r = m.index(a + 1, b + 1),
                          t = m.index(a, b + 1);
      m.triangles.push_back({p, q, r});
      m.triangles.push_back({p, r, t});
    }
  // Poles: area-weighted mean of the triangle normals around the vertex.
  if (std::find(analytic.begin(), analytic.end(), false) != analytic.end()) {
    std::vector<Point> sum(n, Point::Zero());
    for (const auto& tri : m.triangles) {
      const Point f =
          (m.vertices[tri[1]] - m.vertices[tri[0]]).cross(m.vertices[tri[2]] - m.vertices[tri[0]]);
      for (auto k : tri) sum[k] += f;
    }
    for (std::size_t k = 0; k < n; ++k)
      if (!analytic[k]) m.normals[k] = sum[k].norm() > 0 ? sum[k].normalized() : Point(0, 0, 1);
  }
  return m;
}

Curvature curvature(const Surface& s, double u, double v) {
  Point d[6];
  s.derivatives(u, v, d);
  const Point c = d[1].cross(d[2]);
  Curvature k;
  if (!(c.norm() > 1e-12 * d[1].norm() * d[2].norm()) || c.norm() == 0) {
    k.mean = k.gaussian = std::numeric_limits<double>::quiet_NaN();
    return k;
  }
  const Point nrm = c.normalized();
  const double E = d[1].dot(d[1]), F = d[1].dot(d[2]), G = d[2].dot(d[2]);
  const double L = d[3].dot(nrm), M = d[4].dot(nrm), N = d[5].dot(nrm);
  const double det = E * G - F * F;
  k.gaussian = (L * N - M * M) / det;
  k.mean = (E * N - 2 * F * M + G * L) / (2 * det);
  return k;
}

}  // namespace sfit::exchange
