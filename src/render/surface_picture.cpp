#include "sfit/render/surface_picture.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <numeric>

#include "nearest.h"
#include "raster.h"
#include "sfit/error.h"
#include "sfit/render/colormap.h"
#include "sfit/render/deviations.h"
#include "text.h"

namespace sfit::render {

Mode parse_mode(const std::string& text, const std::string& option) {
  if (text == "shaded") return Mode::kShaded;
  if (text == "zebra") return Mode::kZebra;
  if (text == "deviation") return Mode::kDeviation;
  if (text == "gauss") return Mode::kGauss;
  if (text == "mean") return Mode::kMean;
  throw Error(ErrorCode::kUsage,
              "'" + text + "' is not a mode: give shaded, zebra, deviation, gauss or mean",
              Place{.option = option});
}

const char* to_string(Mode m) {
  switch (m) {
    case Mode::kShaded:
      return "shaded";
    case Mode::kZebra:
      return "zebra";
    case Mode::kDeviation:
      return "deviation";
    case Mode::kGauss:
      return "gauss";
    case Mode::kMean:
      return "mean";
  }
  return "shaded";
}

namespace {

using detail::Align;
using detail::Weight;
using Eigen::Vector3d;
using Eigen::Vector3f;

constexpr Rgb kBackground{255, 255, 255};
constexpr Rgb kInk{30, 30, 30};
// Surface colours stay below the background's white, so a picture shows where it was drawn.
constexpr float kMaxShade = 250.f / 255.f;

[[noreturn]] void bad(const std::string& field, const std::string& why, double value) {
  throw Error(ErrorCode::kUsage, why, Place{.option = field}, {value});
}

void validate(const Scene& sc, const RenderOptions& o) {
  if (!sc.surface) throw Error(ErrorCode::kInternal, "render_surface: no surface");
  if (o.width < 64 || o.width > 4096) bad("width", "picture width must be 64 ... 4096", o.width);
  if (o.height < 64 || o.height > 4096)
    bad("height", "picture height must be 64 ... 4096", o.height);
  if (o.supersample < 1 || o.supersample > 4)
    bad("supersample", "supersampling must be 1 ... 4", o.supersample);
  if (!(o.exaggeration > 0) || !std::isfinite(o.exaggeration))
    bad("exaggeration", "exaggeration must be a finite number > 0", o.exaggeration);
  if (!(o.stripes > 0) || o.stripes > 1000)
    bad("stripes", "stripes must be > 0 and <= 1000", o.stripes);
  if (!(o.curvature_scale >= 0) || !std::isfinite(o.curvature_scale))
    bad("curvature_scale", "curvature scale must be a finite number >= 0", o.curvature_scale);
  // A surface of no size (one point) or beyond double's squares leaves no camera to place:
  // refuse it rather than search for a view for minutes and draw noise.
  {
    Point lo = Point::Constant(INFINITY), hi = Point::Constant(-INFINITY);
    for (const Point& p : sc.surface->control) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const double size = sc.surface->control.empty() ? 0.0 : (hi - lo).norm();
    if (!(size >= 1e-150 && size <= 1e150))
      throw Error(ErrorCode::kInputData,
                  size == 0 ? std::string("the surface is a single point: nothing to draw")
                            : "the surface's size " + std::to_string(size) +
                                  " is out of the range sfit draws (1e-150 ... 1e150)",
                  Place{}, {size});
  }
  const std::size_t n = sc.rows ? sc.rows->total_points() : 0;
  if ((o.points || o.mode == Mode::kDeviation) && !sc.rows)
    bad(o.points ? "points" : "mode", "this picture needs the data points", 0);
  if (o.mode == Mode::kDeviation && sc.deviations.size() != n)
    bad("mode", "the deviation picture needs one deviation per data point",
        static_cast<double>(sc.deviations.size()));
  if (o.rows && (!sc.rows || sc.row_v.size() != sc.rows->size()))
    bad("rows", "the row curves need the data rows and their v parameters",
        static_cast<double>(sc.row_v.size()));
  const Surface& s = *sc.surface;
  if (s.count_u < 1 || s.count_v < 1 ||
      s.control.size() != static_cast<std::size_t>(s.count_u) * s.count_v)
    throw Error(ErrorCode::kInputData, "the surface has no control points or a wrong count",
                Place{}, {static_cast<double>(s.count_u), static_cast<double>(s.count_v)});
}

std::string fmt_g(double x, int digits = 3) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  std::string s = buf;
  if (!s.empty() && s[0] == '-') s = "\xE2\x88\x92" + s.substr(1);  // U+2212 minus
  return s;
}

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

}  // namespace

RenderResult render_surface(const Scene& sc, const RenderOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  validate(sc, o);
  RenderResult res;
  // Samples cost about 48 bytes each: past some 12 million, fewer samples per pixel.
  const int W = o.width, H = o.height;
  const int SS = std::clamp(static_cast<int>(std::sqrt(12e6 / (static_cast<double>(W) * H))), 1,
                            o.supersample);
  res.supersample = SS;

  // The surface in exaggerated coordinates (B-splines are affine invariant: scaling the
  // control points scales the surface).
  Surface s = *sc.surface;
  for (Point& p : s.control) p[o.view.up_axis] *= o.exaggeration;
  Camera cam = Camera::looking(o.view, o.exaggeration);
  const auto to_screen = [&](const Point& pe) {  // exaggerated point -> (x, y, depth) in pixels
    return Vector3d(cam.origin.x() + cam.scale * pe.dot(cam.right),
                    cam.origin.y() - cam.scale * pe.dot(cam.up), pe.dot(cam.toward));
  };

  // Layout: title at the top, colour bar on the right, notes at the bottom.
  const bool has_bar =
      o.mode == Mode::kDeviation || o.mode == Mode::kGauss || o.mode == Mode::kMean;
  const int lh = detail::line_height();
  const int title_h = o.title.empty() ? 0 : 6 + static_cast<int>(o.title.size()) * (lh + 2);
  const int footer_h = o.mode == Mode::kShaded ? 0 : lh + 8;
  const int bar_w = has_bar ? 96 : 0;
  res.plot_x0 = 0;
  res.plot_y0 = title_h;
  res.plot_x1 = W - bar_w;
  res.plot_y1 = H - footer_h;

  // A coarse grid of the surface (4 samples a knot span at least) fits the camera.
  const double ue = s.u_end(), ve = s.v_end();
  const int cu = std::clamp(4 * static_cast<int>(std::ceil(ue)), 24, 256);
  const int cv = std::clamp(4 * static_cast<int>(std::ceil(ve)), 24, 256);
  std::vector<Point> fit_points;
  fit_points.reserve(static_cast<std::size_t>(cu + 1) * (cv + 1));
  for (int i = 0; i <= cu; ++i)
    for (int j = 0; j <= cv; ++j) fit_points.push_back(s.evaluate(ue * i / cu, ve * j / cv));
  const std::size_t n_surface_fit = fit_points.size();
  if (o.net)
    for (const Point& p : s.control) fit_points.push_back(p);
  const bool show_points = o.points || o.mode == Mode::kDeviation;
  if (show_points)
    for (const Point& p : sc.rows->points()) fit_points.push_back(cam.exaggerate(p));
  cam.fit(fit_points, res.plot_x0, res.plot_y0, res.plot_x1, res.plot_y1, 0.04);

  // Tessellation fine enough that an edge spans about 3 pixels on the picture.
  double len_u = 0, len_v = 0;
  for (int j = 0; j <= cv; ++j) {
    double l = 0;
    for (int i = 0; i < cu; ++i)
      l += (to_screen(fit_points[(i + 1) * (cv + 1) + j]) - to_screen(fit_points[i * (cv + 1) + j]))
               .head<2>()
               .norm();
    len_u = std::max(len_u, l);
  }
  for (int i = 0; i <= cu; ++i) {
    double l = 0;
    for (int j = 0; j < cv; ++j)
      l += (to_screen(fit_points[i * (cv + 1) + j + 1]) - to_screen(fit_points[i * (cv + 1) + j]))
               .head<2>()
               .norm();
    len_v = std::max(len_v, l);
  }
  const int nu = std::clamp(static_cast<int>(std::ceil(len_u / 3)), cu, 1200);
  const int nv = std::clamp(static_cast<int>(std::ceil(len_v / 3)), cv, 1200);
  // Deviation mode: each data point's ratio |d|/T, and the surface tinted by the ratio of
  // the data point nearest each vertex (the points themselves are drawn in exact colours).
  const std::size_t n_points = sc.rows ? sc.rows->total_points() : 0;
  std::vector<double> ratio;
  std::unique_ptr<detail::NearestPoint> nearest;
  if (o.mode == Mode::kDeviation && n_points) {
    ratio.resize(n_points);
    std::vector<Point> pe(n_points);
    for (std::size_t k = 0; k < n_points; ++k) {
      ratio[k] = tolerance_ratio(sc.deviations[k], sc.tolerance, sc.zero_scale);
      pe[k] = cam.exaggerate(sc.rows->points()[k]);
    }
    nearest = std::make_unique<detail::NearestPoint>(std::move(pe));
  }
  std::vector<detail::ScreenVertex> vert(static_cast<std::size_t>(nu + 1) * (nv + 1));
  auto vid = [nv](int i, int j) { return static_cast<std::size_t>(i) * (nv + 1) + j; };
  double depth_lo = INFINITY, depth_hi = -INFINITY;
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      const double u = ue * i / nu, v = ve * j / nv;
      // A closed direction's last column is its first one, bit for bit: no seam can open.
      const int si = s.periodic_u && i == nu ? 0 : i;
      const int sj = s.periodic_v && j == nv ? 0 : j;
      Vector3d q;
      double attr = 0;
      if (si != i || sj != j) {
        const auto& w = vert[vid(si, sj)];
        q = Vector3d(w.x / SS, w.y / SS, w.depth);
        attr = w.attr;
      } else {
        const Point p = s.evaluate(u, v);
        q = to_screen(p);
        if (nearest) attr = ratio[nearest->nearest(p)];
      }
      vert[vid(i, j)] = {q.x() * SS, q.y() * SS, q.z(), u, v, attr};
      depth_lo = std::min(depth_lo, q.z());
      depth_hi = std::max(depth_hi, q.z());
    }
  // Unit world length in picture pixels and the depth slack of overlays.
  const double extent = std::max(depth_hi - depth_lo, 1e-300) +
                        std::max(res.plot_x1 - res.plot_x0, res.plot_y1 - res.plot_y0) / cam.scale;
  const double slack = 0.004 * extent;

  detail::GBuffer g(W * SS, H * SS);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      detail::rasterize_triangle(g, vert[vid(i, j)], vert[vid(i + 1, j)], vert[vid(i + 1, j + 1)]);
      detail::rasterize_triangle(g, vert[vid(i, j)], vert[vid(i + 1, j + 1)], vert[vid(i, j + 1)]);
    }
  vert.clear();
  vert.shrink_to_fit();

  // Shading: the exact derivatives at each covered sample's (u, v).
  // A key light above left of the eye and a weaker fill light below right: every face that
  // looks at the viewer is lit.
  const Lights lights{(-0.30 * cam.right + 0.40 * cam.up + 0.87 * cam.toward).normalized(),
                      (0.55 * cam.right - 0.25 * cam.up + 0.80 * cam.toward).normalized()};
  const Vector3d half = (lights.key + cam.toward).normalized();
  const std::size_t NS = g.depth.size();
  std::vector<Vector3f> normal(NS, Vector3f::Zero());  // facing the viewer
  std::vector<double> value(NS, NAN);                  // curvature or stripe coordinate
  std::vector<double> samples;                         // curvature values for the scale
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
  double angle = o.stripe_angle * std::numbers::pi / 180;
  if (std::isnan(o.stripe_angle)) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < n_surface_fit; ++i)
      mean += Eigen::Vector2d(fit_points[i].dot(cam.right), fit_points[i].dot(cam.up));
    mean /= static_cast<double>(n_surface_fit);
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (std::size_t i = 0; i < n_surface_fit; ++i) {
      const Eigen::Vector2d d =
          Eigen::Vector2d(fit_points[i].dot(cam.right), fit_points[i].dot(cam.up)) - mean;
      cov += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
    const Eigen::Vector2d major = eig.eigenvectors().col(1);  // (right, up) components
    // A roundish outline has no long axis: keep the lines vertical then.
    angle =
        eig.eigenvalues()(1) > 2.0 * eig.eigenvalues()(0) ? std::atan2(major.x(), major.y()) : 0.0;
    if (angle > std::numbers::pi / 2) angle -= std::numbers::pi;
    if (angle < -std::numbers::pi / 2) angle += std::numbers::pi;
  }
  res.stripe_angle = angle * 180 / std::numbers::pi;
  const Vector3d across = std::cos(angle) * cam.right - std::sin(angle) * cam.up;
  double lo_x = INFINITY, hi_x = -INFINITY;
  for (std::size_t i = 0; i < n_surface_fit; ++i) {
    lo_x = std::min(lo_x, fit_points[i].dot(across));
    hi_x = std::max(hi_x, fit_points[i].dot(across));
  }
  const double world_w = std::max(hi_x - lo_x, 1e-300);
  const double stripe_h = world_w / (2 * o.stripes);  // width of one stripe
  const double height = 6 * stripe_h;
  for (std::size_t k = 0; k < NS; ++k) {
    if (!g.covered(k)) continue;
    const Local l = local_geometry(s, g.u[k], g.v[k]);
    Vector3d n = l.normal;
    if (n.dot(cam.toward) < 0) n = -n;
    normal[k] = n.cast<float>();
    switch (o.mode) {
      case Mode::kGauss:
        value[k] = l.gauss;
        break;
      case Mode::kMean:
        value[k] = l.mean;
        break;
      case Mode::kZebra: {
        const double nt = std::max(n.dot(cam.toward), 1e-9);
        value[k] = l.p.dot(across) + height * n.dot(across) / nt;
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
        if (g.covered(k)) value[k] = world_w * std::asinh((value[k] - m) / world_w);
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
    samples.clear();
  }
  if (o.mode == Mode::kDeviation) res.scale = 1;

  detail::ColorBuffer cb(W * SS, H * SS, detail::to_float(kBackground));
  const Vector3f base_shaded(0.70f, 0.75f, 0.83f), base_grey(0.80f, 0.80f, 0.80f);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::size_t k = g.index(x, y);
      if (!g.covered(k)) continue;
      const Vector3d n = normal[k].cast<double>();
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
          const Vector3f tint = detail::to_float(t > 1 + 1e-9 ? kExceeded : sequential(t));
          c = tint * static_cast<float>(0.6 + 0.4 * light);
          break;
        }
        case Mode::kGauss:
        case Mode::kMean: {
          const float lit = static_cast<float>(0.70 + 0.30 * key);
          c = detail::to_float(diverging(value[k] / res.scale)) * lit;
          break;
        }
        case Mode::kZebra: {
          // Filter width: how fast the highlight coordinate changes from sample to sample.
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
          c = Vector3f::Constant(static_cast<float>(0.07 + t * (white - 0.07)));
          break;
        }
      }
      cb.at(x, y) = c.cwiseMax(0.f).cwiseMin(kMaxShade);
    }
  normal.clear();
  value.clear();

  // Overlays, on the samples, against the surface's depth.
  const auto sample_pos = [&](const Point& pe) {
    Vector3d q = to_screen(pe);
    q.x() *= SS;
    q.y() *= SS;
    return q;
  };
  const double px = SS;  // one picture pixel in samples
  if (o.rows) {
    const detail::DepthTest t{&g, slack, 0.f};
    const Vector3f blue(0.08f, 0.22f, 0.60f);
    const int n = 2 * nu;
    for (double v : sc.row_v) {
      Vector3d prev = sample_pos(s.evaluate(0, v));
      for (int i = 1; i <= n; ++i) {
        const Vector3d q = sample_pos(s.evaluate(ue * i / n, v));
        detail::draw_segment(cb, prev, q, 0.75 * px, blue, t);
        prev = q;
      }
    }
  }
  if (o.net) {
    const detail::DepthTest t{&g, slack, 0.3f};
    const Vector3f red(0.78f, 0.12f, 0.08f);
    const int fu = s.periodic_u ? s.count_u : s.count_u - 1,
              fv = s.periodic_v ? s.count_v : s.count_v - 1;
    for (int i = 0; i < s.count_u; ++i)
      for (int j = 0; j < s.count_v; ++j) {
        const Vector3d a = sample_pos(s.at(i, j));
        if (i < fu)
          detail::draw_segment(cb, a, sample_pos(s.at((i + 1) % s.count_u, j)), 0.6 * px, red, t);
        if (j < fv)
          detail::draw_segment(cb, a, sample_pos(s.at(i, (j + 1) % s.count_v)), 0.6 * px, red, t);
      }
    for (const Point& p : s.control) detail::draw_disc(cb, sample_pos(p), 1.8 * px, red, t);
  }
  const double plot_area =
      static_cast<double>(res.plot_x1 - res.plot_x0) * (res.plot_y1 - res.plot_y0);
  const double radius =
      n_points ? std::clamp(0.22 * std::sqrt(plot_area / static_cast<double>(n_points)), 1.6, 4.0)
               : 2;
  if (o.mode == Mode::kDeviation) {
    std::vector<std::size_t> order(n_points);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](auto a, auto b) { return ratio[a] < ratio[b]; });
    const detail::DepthTest t{&g, slack, 0.f};
    const Vector3f outline(0.3f, 0.3f, 0.3f);
    // Sparse points get a dark rim; dense ones merge into the tinted surface.
    const double rim = radius >= 2.5 ? 0.7 : 0.0;
    for (std::size_t k : order) {
      const Rgb c = ratio[k] > 1 + 1e-9 ? kExceeded : sequential(ratio[k]);
      const Vector3d q = sample_pos(cam.exaggerate(sc.rows->points()[k]));
      if (rim > 0) detail::draw_disc(cb, q, (radius + rim) * px, outline, t);
      detail::draw_disc(cb, q, radius * px, detail::to_float(c), t);
    }
    if (n_points) {
      res.worst_point = static_cast<long>(order.back());
      res.worst_ratio = ratio[order.back()];
      // The worst point is always shown, even where the surface hides it.
      const std::size_t k = order.back();
      const Rgb c = ratio[k] > 1 + 1e-9 ? kExceeded : sequential(ratio[k]);
      const Vector3d q = sample_pos(cam.exaggerate(sc.rows->points()[k]));
      detail::draw_disc(cb, q, (radius + 0.7) * px, outline, {});
      detail::draw_disc(cb, q, radius * px, detail::to_float(c), {});
    }
  } else if (o.points) {
    const detail::DepthTest t{&g, slack, 0.f};
    for (const Point& p : sc.rows->points())
      detail::draw_disc(cb, sample_pos(cam.exaggerate(p)), std::min(radius, 2.2) * px,
                        Vector3f(0.1f, 0.1f, 0.1f), t);
  }

  Image img = detail::downsample(cb, SS);
  res.camera = cam;

  if (res.worst_point >= 0) {
    const Vector3d q = cam.project(sc.rows->points()[res.worst_point]);
    detail::draw_ring(img, q.x(), q.y(), radius + 3.5, 1.6, kInk);
  }

  // Title.
  for (std::size_t i = 0; i < o.title.size(); ++i)
    detail::draw_text(img, 8, 4 + static_cast<int>(i) * (lh + 2) + detail::ascent(), o.title[i],
                      kInk, i == 0 ? Weight::kBold : Weight::kRegular);

  // Colour bar.
  if (has_bar) {
    const int bx0 = W - bar_w + 14, bx1 = bx0 + 16;
    const int by0 = res.plot_y0 + 2 * lh + 12, by1 = res.plot_y1 - lh;
    res.bar_x0 = bx0;
    res.bar_x1 = bx1;
    res.bar_y0 = by0;
    res.bar_y1 = by1;
    const bool dev = o.mode == Mode::kDeviation;
    for (int y = by0; y < by1; ++y) {
      const double t = 1.0 - (y + 0.5 - by0) / (by1 - by0);  // 1 at the top
      detail::fill_rect(img, bx0, y, bx1, y + 1, dev ? sequential(t) : diverging(2 * t - 1));
    }
    const int tx = bx1 + 5;
    auto tick = [&](double t, const std::string& label) {
      const int y = static_cast<int>(std::lround(by1 - t * (by1 - by0)));
      detail::fill_rect(img, bx1, y, bx1 + 3, y + 1, kInk);
      detail::draw_text(img, tx, y + detail::ascent() / 2 - 1, label, kInk);
    };
    std::string head;
    if (dev) {
      head = "|d| / T";
      tick(0, "0");
      tick(0.5, "0.5 T");
      tick(1, "T");
      if (res.worst_ratio > 1 + 1e-9) {
        detail::fill_rect(img, bx0, by0 - 14, bx1, by0 - 4, kExceeded);
        detail::draw_text(img, tx, by0 - 5, "> T", kInk);
      }
    } else {
      head = o.mode == Mode::kGauss ? "K" : "H";
      tick(1, "+" + fmt_g(res.scale));
      tick(0.5, "0");
      tick(0, fmt_g(-res.scale));
    }
    detail::draw_text(img, bx0, res.plot_y0 + lh + 4, head, kInk, Weight::kBold);
  }

  // Notes at the bottom.
  std::string note;
  switch (o.mode) {
    case Mode::kShaded:
      break;
    case Mode::kZebra:
      note = "highlight stripes: " + fmt_g(o.stripes) + " pairs across the surface, light lines " +
             (std::abs(res.stripe_angle) < 0.05
                  ? std::string("vertical")
                  : fmt_g(res.stripe_angle, 2) + "\xC2\xB0 from vertical");
      break;
    case Mode::kDeviation:
      if (n_points) {
        const auto& off = sc.rows->offsets();
        const long row =
            static_cast<long>(std::upper_bound(off.begin(), off.end(), res.worst_point) -
                              off.begin()) -
            1;
        note = "max |d|/T " + fmt_g(res.worst_ratio) + " at row " + std::to_string(row) +
               ", point " + std::to_string(res.worst_point - static_cast<long>(off[row]));
        if (!sc.deviation_note.empty()) note += " (" + sc.deviation_note + ")";
      }
      break;
    case Mode::kGauss:
    case Mode::kMean:
      note = std::string(o.mode == Mode::kGauss ? "K" : "H") + " from " + fmt_g(res.value_min) +
             " to " + fmt_g(res.value_max) + "; colours " + "\xC2\xB1" + fmt_g(res.scale) +
             (o.curvature_scale > 0 ? "" : " (95th percentile of |value|)");
      if (o.mode == Mode::kMean) note += "; normal S_u \xC3\x97 S_v";
      break;
  }
  if (o.exaggeration != 1.0)
    note += (note.empty() ? "" : "; ") + std::string("up axis \xC3\x97 ") + fmt_g(o.exaggeration);
  if (!note.empty()) detail::draw_text(img, 8, H - 6, note, kInk);

  res.image = std::move(img);
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace sfit::render
