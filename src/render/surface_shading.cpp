#include "surface_shading.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "sfit/render/colormap.h"

namespace sfit::render::detail {

namespace {

using Eigen::Vector3d;
using Eigen::Vector3f;

constexpr Rgb kBackground{255, 255, 255};
// Surface colours stay below the background's white, so a picture shows where it was drawn.
constexpr float kMaxShade = 250.f / 255.f;

struct Lights {
  Vector3d key, fill;
};

// Surface geometry at a sample: the exact derivatives there.
struct Local {
  Point p;
  Vector3d normal;  // unit S_u x S_v (may be zero at a degenerate point)
  double gauss = NAN, mean = NAN;
};

Local local_geometry(const Surface& s, double u, double v) {
  Point d[6];
  s.derivatives(u, v, d);
  Vector3d n = d[1].cross(d[2]);
  const double scale2 = d[1].squaredNorm() * d[2].squaredNorm();
  Local l;
  l.p = d[0];
  if (!(n.squaredNorm() > 1e-20 * scale2) || scale2 == 0) {
    // A pole or a collapsed edge: take the normal a little inside the domain.
    const double du = 1e-6 * std::max(1.0, s.u_end()), dv = 1e-6 * std::max(1.0, s.v_end());
    Point e[6];
    s.derivatives(u < 0.5 * s.u_end() ? u + du : u - du, v < 0.5 * s.v_end() ? v + dv : v - dv, e);
    n = e[1].cross(e[2]);
    l.normal = n.squaredNorm() > 0 ? Vector3d(n.normalized()) : Vector3d::Zero();
    return l;  // curvature undefined here
  }
  const double E = d[1].dot(d[1]), F = d[1].dot(d[2]), G = d[2].dot(d[2]);
  n.normalize();
  const double L = d[3].dot(n), M = d[4].dot(n), N = d[5].dot(n);
  const double det = E * G - F * F;
  l.normal = n;
  l.gauss = (L * N - M * M) / det;
  l.mean = (E * N - 2 * F * M + G * L) / (2 * det);
  return l;
}

// The integral of the stripe function (1 on [0, h), 0 on [h, 2h), period 2h) from 0 to x.
double stripe_integral(double x, double h) {
  const double n = std::floor(x / (2 * h));
  return n * h + std::min(x - n * 2 * h, h);
}

// Box-filtered stripe value over [w - fw/2, w + fw/2]: anti-aliased, and grey where the
// stripes are finer than a sample.
double filtered_stripe(double w, double fw, double h) {
  if (fw >= 2 * h) return 0.5;
  if (fw < 1e-9 * h) return stripe_integral(w + 1e-9 * h, h) > stripe_integral(w, h) ? 1.0 : 0.0;
  return (stripe_integral(w + fw / 2, h) - stripe_integral(w - fw / 2, h)) / fw;
}

double percentile_abs(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  for (double& x : values) x = std::abs(x);
  const std::size_t k = std::min(values.size() - 1, static_cast<std::size_t>(q * values.size()));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

// Highlight lines after Beier and Chen (1994): parallel light lines in a plane normal to
// the view, a height h above each point; the point's highlight is where its normal line
// meets that plane, and its coordinate across the lines is x = P.a + h (N.a) / (N.t)
// (a across the lines, t towards the eye). On a plane x is linear in P: straight, parallel,
// evenly spaced stripes. On a curved surface the normal bends them: h = 6 stripe widths, so
// a stripe stands for about 10 degrees of turn near the middle. (Beier and Chen keep the
// light plane fixed; a fixed height keeps deep scenes, a blade seen along its span, from
// running to noise.) Towards the silhouette x runs off to infinity, so it is read through
// D asinh((x - m) / D), with m its median and D the surface's extent across the lines:
// linear in the middle, logarithmic far out. The lines run along the surface's longer axis
// on the picture (or at stripe_angle from the vertical).
struct Stripes {
  Vector3d across;  // across the lines
  double world_w;   // D: the surface's extent across them
  double stripe_h;  // the width of one stripe
  double height;    // h
};

// The light lines' angle from the vertical in radians: o.stripe_angle, or along the picture's
// longer axis of the coarse grid (vertical where the outline is roundish).
double stripe_angle(const RenderOptions& o, const SurfaceView& view) {
  double angle = o.stripe_angle * std::numbers::pi / 180;
  if (!std::isnan(o.stripe_angle)) return angle;
  const Camera& cam = view.cam;
  const std::vector<Point>& fp = view.fit_points;
  const std::size_t n = view.n_surface_fit;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < n; ++i)
    mean += Eigen::Vector2d(fp[i].dot(cam.right), fp[i].dot(cam.up));
  mean /= static_cast<double>(n);
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d d = Eigen::Vector2d(fp[i].dot(cam.right), fp[i].dot(cam.up)) - mean;
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Eigen::Vector2d major = eig.eigenvectors().col(1);  // (right, up) components
  // A roundish outline has no long axis: keep the lines vertical then.
  angle =
      eig.eigenvalues()(1) > 2.0 * eig.eigenvalues()(0) ? std::atan2(major.x(), major.y()) : 0.0;
  if (angle > std::numbers::pi / 2) angle -= std::numbers::pi;
  if (angle < -std::numbers::pi / 2) angle += std::numbers::pi;
  return angle;
}

// The highlight lines of the picture; sets res.stripe_angle.
Stripes stripes_of(const RenderOptions& o, const SurfaceView& view, RenderResult& res) {
  const double angle = stripe_angle(o, view);
  res.stripe_angle = angle * 180 / std::numbers::pi;
  const Camera& cam = view.cam;
  Stripes st;
  st.across = std::cos(angle) * cam.right - std::sin(angle) * cam.up;
  double lo_x = INFINITY, hi_x = -INFINITY;
  for (std::size_t i = 0; i < view.n_surface_fit; ++i) {
    lo_x = std::min(lo_x, view.fit_points[i].dot(st.across));
    hi_x = std::max(hi_x, view.fit_points[i].dot(st.across));
  }
  st.world_w = std::max(hi_x - lo_x, 1e-300);
  st.stripe_h = st.world_w / (2 * o.stripes);
  st.height = 6 * st.stripe_h;
  return st;
}

// Per sample: the normal facing the viewer, and the curvature (gauss, mean) or the highlight
// coordinate (zebra) of the mode.
struct SampleValues {
  std::vector<Vector3f> normal;
  std::vector<double> value;
};

SampleValues sample_values(const RenderOptions& o, const SurfaceView& view, const GBuffer& g,
                           const Stripes& st, RenderResult& res) {
  const Camera& cam = view.cam;
  const std::size_t NS = g.depth.size();
  SampleValues sv{std::vector<Vector3f>(NS, Vector3f::Zero()), std::vector<double>(NS, NAN)};
  std::vector<double>& value = sv.value;
  std::vector<double> samples;  // curvature values for the scale
  for (std::size_t k = 0; k < NS; ++k) {
    if (!g.covered(k)) continue;
    const Local l = local_geometry(view.s, g.u[k], g.v[k]);
    Vector3d n = l.normal;
    if (n.dot(cam.toward) < 0) n = -n;
    sv.normal[k] = n.cast<float>();
    switch (o.mode) {
      case Mode::kGauss:
        value[k] = l.gauss;
        break;
      case Mode::kMean:
        value[k] = l.mean;
        break;
      case Mode::kZebra: {
        const double nt = std::max(n.dot(cam.toward), 1e-9);
        value[k] = l.p.dot(st.across) + st.height * n.dot(st.across) / nt;
        break;
      }
      default:
        break;
    }
    if ((o.mode == Mode::kGauss || o.mode == Mode::kMean) && std::isfinite(value[k]))
      samples.push_back(value[k]);
  }
  if (o.mode == Mode::kZebra) {
    std::vector<double> xs;
    for (std::size_t k = 0; k < NS; ++k)
      if (g.covered(k)) xs.push_back(value[k]);
    if (!xs.empty()) {
      std::nth_element(xs.begin(), xs.begin() + static_cast<std::ptrdiff_t>(xs.size() / 2),
                       xs.end());
      const double m = xs[xs.size() / 2];
      for (std::size_t k = 0; k < NS; ++k)
        if (g.covered(k)) value[k] = st.world_w * std::asinh((value[k] - m) / st.world_w);
    }
  }
  if (o.mode == Mode::kGauss || o.mode == Mode::kMean) {
    if (!samples.empty()) {
      const auto [lo, hi] = std::minmax_element(samples.begin(), samples.end());
      res.value_min = *lo;
      res.value_max = *hi;
    }
    res.scale = o.curvature_scale > 0 ? o.curvature_scale : percentile_abs(samples, 0.95);
    if (!(res.scale > 0))
      res.scale = std::max({std::abs(res.value_min), std::abs(res.value_max), 1e-300});
  }
  if (o.mode == Mode::kDeviation) res.scale = 1;
  return sv;
}

// Zebra: the stripe at sample (x, y), box-filtered over how fast the highlight coordinate
// changes from sample to sample, white by the key light.
Vector3f zebra_colour(const GBuffer& g, const std::vector<double>& value, int x, int y,
                      double stripe_h, double key) {
  const std::size_t k = g.index(x, y);
  double fw = 0;
  auto diff = [&](int dx, int dy) -> double {
    const int x2 = x + dx, y2 = y + dy;
    if (x2 < 0 || y2 < 0 || x2 >= g.width || y2 >= g.height) return std::nan("");
    const std::size_t k2 = g.index(x2, y2);
    return g.covered(k2) ? std::abs(value[k2] - value[k]) : std::nan("");
  };
  for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
    const double d = diff(dx, dy);
    if (std::isfinite(d)) fw = std::max(fw, d);
  }
  const double t = filtered_stripe(value[k], fw, stripe_h);
  const float white = static_cast<float>(0.80 + 0.20 * key);
  return Vector3f::Constant(static_cast<float>(0.07 + t * (white - 0.07)));
}

}  // namespace

ColorBuffer shade_surface(const RenderOptions& o, const SurfaceView& view, const GBuffer& g,
                          RenderResult& res) {
  const Camera& cam = view.cam;
  // A key light above left of the eye and a weaker fill light below right: every face that
  // looks at the viewer is lit.
  const Lights lights{(-0.30 * cam.right + 0.40 * cam.up + 0.87 * cam.toward).normalized(),
                      (0.55 * cam.right - 0.25 * cam.up + 0.80 * cam.toward).normalized()};
  const Vector3d half = (lights.key + cam.toward).normalized();
  const Stripes st = stripes_of(o, view, res);
  const SampleValues sv = sample_values(o, view, g, st, res);

  ColorBuffer cb(o.width * view.ss, o.height * view.ss, to_float(kBackground));
  const Vector3f base_shaded(0.70f, 0.75f, 0.83f);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::size_t k = g.index(x, y);
      if (!g.covered(k)) continue;
      const Vector3d n = sv.normal[k].cast<double>();
      const double key = std::max(0.0, n.dot(lights.key)), fill = std::max(0.0, n.dot(lights.fill));
      const double spec = std::pow(std::max(0.0, n.dot(half)), 32);
      const float light = static_cast<float>(0.30 + 0.55 * key + 0.22 * fill);
      Vector3f c = Vector3f::Zero();
      switch (o.mode) {
        case Mode::kShaded:
          c = base_shaded * light + Vector3f::Constant(static_cast<float>(0.20 * spec));
          break;
        case Mode::kDeviation: {
          const double t = g.attr[k];
          const Vector3f tint = to_float(t > 1 + 1e-9 ? kExceeded : sequential(t));
          c = tint * static_cast<float>(0.6 + 0.4 * light);
          break;
        }
        case Mode::kGauss:
        case Mode::kMean: {
          const float lit = static_cast<float>(0.70 + 0.30 * key);
          c = to_float(diverging(sv.value[k] / res.scale)) * lit;
          break;
        }
        case Mode::kZebra:
          c = zebra_colour(g, sv.value, x, y, st.stripe_h, key);
          break;
      }
      cb.at(x, y) = c.cwiseMax(0.f).cwiseMin(kMaxShade);
    }
  return cb;
}

}  // namespace sfit::render::detail
