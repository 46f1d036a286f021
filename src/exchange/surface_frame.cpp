#include "surface_frame.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace sfit::exchange::detail {

namespace {

constexpr double kNudge = 1e-4;  // parameter step beside a degenerate point (knot spans are 1)

// Parameters beside (u, v), nudged inward: along v, along u, along both.
template <typename F>
bool beside(const Surface& s, double u, double v, F&& try_at) {
  const double du = u < s.u_end() / 2 ? kNudge : -kNudge;
  const double dv = v < s.v_end() / 2 ? kNudge : -kNudge;
  return try_at(u, v + dv) || try_at(u + du, v) || try_at(u + du, v + dv);
}

}  // namespace

SurfaceFrame::SurfaceFrame(const Surface& s) : scaled(s) {
  if (s.control.empty()) return;
  Point lo = s.control.front(), hi = lo;
  for (const Point& p : s.control) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  centre = lo / 2 + hi / 2;  // halves first: no overflow near the largest doubles
  double m = 0;
  for (const Point& p : s.control) m = std::max(m, (p - centre).cwiseAbs().maxCoeff());
  if (m > 0 && std::isfinite(m)) size = std::ldexp(1.0, std::ilogb(m) + 1);
  for (Point& p : scaled.control) p = (p - centre) / size;
}

bool SurfaceFrame::unit_normal(const Point d[6], Point& n) {
  const double a = d[1].norm(), b = d[2].norm();
  if (!(a > 1e-10 && b > 1e-10)) return false;
  const Point c = (d[1] / a).cross(d[2] / b);
  const double sine = c.norm();
  if (!(sine > 1e-8)) return false;
  n = c / sine;
  return true;
}

bool SurfaceFrame::normal_near(double u, double v, Point& n) const {
  auto at = [&](double x, double y) {
    Point d[6];
    derivatives(x, y, d);
    return unit_normal(d, n);
  };
  return at(u, v) || beside(scaled, u, v, at);
}

Curvature SurfaceFrame::curvature(double u, double v) const {
  Curvature k;
  auto at = [&](double x, double y) {
    Point d[6];
    derivatives(x, y, d);
    Point n;
    if (!unit_normal(d, n)) return false;
    const double E = d[1].dot(d[1]), F = d[1].dot(d[2]), G = d[2].dot(d[2]);
    const double L = d[3].dot(n), M = d[4].dot(n), N = d[5].dot(n);
    const double det = E * G - F * F;
    if (!(det > 0)) return false;
    // Curvature of the scaled surface, then of the original: H / size, K / size^2.
    k.gaussian = (L * N - M * M) / det / size / size;
    k.mean = (E * N - 2 * F * M + G * L) / (2 * det) / size;
    return true;
  };
  if (at(u, v)) return k;
  k.limit = true;
  if (beside(scaled, u, v, at)) return k;
  k.mean = k.gaussian = std::numeric_limits<double>::quiet_NaN();
  return k;
}

}  // namespace sfit::exchange::detail
