#include "sfit/render/row_picture.h"

#include <algorithm>
#include <cmath>

#include "raster.h"
#include "sfit/error.h"
#include "text.h"

namespace sfit::render {
namespace {

using detail::Align;
using detail::Weight;
using Eigen::Vector3d;
using Eigen::Vector3f;

constexpr Rgb kInk{30, 30, 30};
const Vector3f kBand(0.99f, 0.84f, 0.60f), kCurve(0.10f, 0.25f, 0.70f),
    kPolygon(0.62f, 0.62f, 0.62f), kPoint(0.08f, 0.08f, 0.08f);
const Vector3f kAxisColour[3] = {
    {0.85f, 0.20f, 0.15f}, {0.20f, 0.60f, 0.20f}, {0.15f, 0.30f, 0.85f}};

struct RowData {
  std::span<const Point> points;
  const Curve* curve;
  std::vector<Point> curve_samples;  // dense samples along the curve (closed: wraps)
  Point bound;
  long worst = -1;
};

// One projection into a w x h picture: world (a, b) -> pixel (ox + s a, oy - s b).
Image draw_projection(const RowData& d, int w, int h, int axis_a, int axis_b, double ox, double oy,
                      double s, int SS) {
  detail::ColorBuffer cb(w * SS, h * SS, Vector3f::Ones());
  auto at = [&](const Point& p) {
    return Vector3d((ox + s * p[axis_a]) * SS, (oy - s * p[axis_b]) * SS, 0.0);
  };
  const detail::DepthTest none{};
  // The band: a box of +-bound around the curve, swept along it (each segment sweeps the
  // convex hull of the box at its two ends).
  const double ba = d.bound[axis_a] * s * SS, bb = d.bound[axis_b] * s * SS;
  if (ba > 0 || bb > 0) {
    for (std::size_t i = 0; i + 1 < d.curve_samples.size(); ++i) {
      const Vector3d p = at(d.curve_samples[i]), q = at(d.curve_samples[i + 1]);
      if (std::max(p.x(), q.x()) + ba < 0 || std::min(p.x(), q.x()) - ba > cb.width ||
          std::max(p.y(), q.y()) + bb < 0 || std::min(p.y(), q.y()) - bb > cb.height)
        continue;  // outside this view (an inset shows a small part)
      std::vector<Eigen::Vector2d> corners;
      for (const Vector3d& e : {p, q})
        for (double sa : {-1.0, 1.0})
          for (double sb : {-1.0, 1.0}) corners.emplace_back(e.x() + sa * ba, e.y() + sb * bb);
      detail::fill_hull(cb, std::move(corners), kBand);
    }
  }
  // Control polygon.
  const auto& ctrl = d.curve->control;
  for (std::size_t i = 0; i + 1 < ctrl.size() + (d.curve->periodic ? 1 : 0); ++i)
    detail::draw_segment(cb, at(ctrl[i]), at(ctrl[(i + 1) % ctrl.size()]), 0.5 * SS, kPolygon,
                         none);
  for (const Point& p : ctrl) {
    const Vector3d c = at(p);
    detail::fill_box(cb, c.x() - 1.6 * SS, c.y() - 1.6 * SS, c.x() + 1.6 * SS, c.y() + 1.6 * SS,
                     kPolygon);
  }
  // Curve.
  for (std::size_t i = 0; i + 1 < d.curve_samples.size(); ++i)
    detail::draw_segment(cb, at(d.curve_samples[i]), at(d.curve_samples[i + 1]), 0.8 * SS, kCurve,
                         none);
  // Points.
  for (const Point& p : d.points) detail::draw_disc(cb, at(p), 2.2 * SS, kPoint, none);
  Image img = detail::downsample(cb, SS);
  if (d.worst >= 0) {
    const Vector3d c = at(d.points[d.worst]) / SS;
    detail::draw_ring(img, c.x(), c.y(), 6.5, 1.6, {220, 30, 30});
  }
  return img;
}

void blit(Image& dst, const Image& src, int x0, int y0) {
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < src.width; ++x)
      if (dst.contains(x0 + x, y0 + y)) dst.set(x0 + x, y0 + y, src.at(x, y));
}

void frame(Image& img, int x0, int y0, int x1, int y1, Rgb c) {
  detail::fill_rect(img, x0, y0, x1, y0 + 1, c);
  detail::fill_rect(img, x0, y1 - 1, x1, y1, c);
  detail::fill_rect(img, x0, y0, x0 + 1, y1, c);
  detail::fill_rect(img, x1 - 1, y0, x1, y1, c);
}

}  // namespace

RowPicture render_row(std::span<const Point> points, const CurveFit& fit, const Point& bound,
                      const RowPictureOptions& o) {
  if (o.width < 256 || o.width > 4096 || o.height < 256 || o.height > 4096)
    throw Error(ErrorCode::kUsage, "picture size must be 256 ... 4096 pixels each way",
                Place{.option = "size"},
                {static_cast<double>(o.width), static_cast<double>(o.height)});
  if (o.supersample < 1 || o.supersample > 4)
    throw Error(ErrorCode::kUsage, "supersampling must be 1 ... 4", Place{.option = "supersample"},
                {static_cast<double>(o.supersample)});
  if (points.empty() || fit.parameters.size() != points.size() || fit.curve.control.empty())
    throw Error(ErrorCode::kInternal, "render_row: the curve fit does not belong to the points",
                Place{},
                {static_cast<double>(points.size()), static_cast<double>(fit.parameters.size())});
  const int W = o.width, H = o.height, SS = o.supersample;
  RowPicture out;
  RowData d{points, &fit.curve, {}, bound, -1};
  const Curve& c = fit.curve;
  const double end = c.domain_end();
  const int n_samples = std::max(400, 16 * c.count());
  for (int i = 0; i <= n_samples; ++i) d.curve_samples.push_back(c.evaluate(end * i / n_samples));

  // Per-point deviations and the worst point.
  const bool zero_bound = !(bound.minCoeff() > 0);
  std::vector<Point> dev(points.size());
  double dev_max = 0;
  for (std::size_t j = 0; j < points.size(); ++j) {
    dev[j] = c.evaluate(fit.parameters[j]) - points[j];
    dev_max = std::max(dev_max, dev[j].cwiseAbs().maxCoeff());
  }
  const double abs_scale = dev_max > 0 ? dev_max : 1;
  std::vector<Point> rel(points.size());
  for (std::size_t j = 0; j < points.size(); ++j) {
    rel[j] = zero_bound ? Point(dev[j] / abs_scale) : Point(dev[j].cwiseQuotient(bound));
    const double r = rel[j].cwiseAbs().maxCoeff();
    if (out.worst_index < 0 || r > out.worst_ratio) {
      out.worst_ratio = r;
      out.worst_index = static_cast<long>(j);
    }
  }
  d.worst = out.worst_index;
  if (zero_bound) out.worst_ratio = dev_max;

  Image img(W, H);
  const int lh = detail::line_height();
  const int title_h = o.title.empty() ? 4 : 6 + static_cast<int>(o.title.size()) * (lh + 2);
  for (std::size_t i = 0; i < o.title.size(); ++i)
    detail::draw_text(img, 8, 4 + static_cast<int>(i) * (lh + 2) + detail::ascent(), o.title[i],
                      kInk, i == 0 ? Weight::kBold : Weight::kRegular);
  const int cw = W / 2, ch = (H - title_h) / 2;
  const char* names[3] = {"top: x \xE2\x86\x92, y \xE2\x86\x91",
                          "front: x \xE2\x86\x92, z \xE2\x86\x91",
                          "side: y \xE2\x86\x92, z \xE2\x86\x91"};
  const int axes[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (int k = 0; k < 4; ++k) {
    const int cx0 = (k % 2) * cw, cy0 = title_h + (k / 2) * ch;
    const int x0 = cx0 + 8, x1 = cx0 + cw - 8, y0 = cy0 + lh + 6, y1 = cy0 + ch - 6;
    if (k == 3) {
      out.plot_x0 = x0;
      out.plot_y0 = y0;
      out.plot_x1 = x1;
      out.plot_y1 = y1;
      continue;
    }
    RowPanel& p = out.panels[k];
    p.x0 = x0;
    p.y0 = y0;
    p.x1 = x1;
    p.y1 = y1;
    p.axis_a = axes[k][0];
    p.axis_b = axes[k][1];
    detail::draw_text(img, x0, cy0 + lh + 1, names[k], kInk, Weight::kBold);
    double lo_a = INFINITY, hi_a = -INFINITY, lo_b = INFINITY, hi_b = -INFINITY;
    auto grow = [&](const Point& q) {
      lo_a = std::min(lo_a, q[p.axis_a] - bound[p.axis_a]);
      hi_a = std::max(hi_a, q[p.axis_a] + bound[p.axis_a]);
      lo_b = std::min(lo_b, q[p.axis_b] - bound[p.axis_b]);
      hi_b = std::max(hi_b, q[p.axis_b] + bound[p.axis_b]);
    };
    for (const Point& q : points) grow(q);
    for (const Point& q : d.curve_samples) grow(q);
    double ext = std::max(hi_a - lo_a, hi_b - lo_b);
    if (!(ext > 0)) ext = 1;
    const double wa = std::max(hi_a - lo_a, 1e-9 * ext), wb = std::max(hi_b - lo_b, 1e-9 * ext);
    const int pw = x1 - x0, ph = y1 - y0;
    p.scale = 0.92 * std::min(pw / wa, ph / wb);
    p.origin_x = x0 + 0.5 * pw - p.scale * 0.5 * (lo_a + hi_a);
    p.origin_y = y0 + 0.5 * ph + p.scale * 0.5 * (lo_b + hi_b);
    blit(img,
         draw_projection(d, pw, ph, p.axis_a, p.axis_b, p.origin_x - x0, p.origin_y - y0, p.scale,
                         SS),
         x0, y0);
    frame(img, x0, y0, x1, y1, {170, 170, 170});
    // Where the band is too thin to see, a magnified inset around the worst point shows it.
    const double band_px = 2 * std::max(bound[p.axis_a], bound[p.axis_b]) * p.scale;
    if (!zero_bound && band_px < 6 && d.worst >= 0) {
      const int iw = pw * 2 / 5, ih = ph * 2 / 5;
      const double is = 0.3 * std::min(iw, ih) / (2 * std::max(bound[p.axis_a], bound[p.axis_b]));
      const Point& q = points[d.worst];
      const double iox = 0.5 * iw - is * q[p.axis_a], ioy = 0.5 * ih + is * q[p.axis_b];
      const int ix0 = x1 - iw - 4, iy0 = y1 - ih - 4;
      blit(img, draw_projection(d, iw, ih, p.axis_a, p.axis_b, iox, ioy, is, SS), ix0, iy0);
      frame(img, ix0, iy0, ix0 + iw, iy0 + ih, {90, 90, 90});
      detail::draw_text(img, ix0 + 4, iy0 + lh, "\xC3\x97" + detail::format_g(is / p.scale, 2),
                        kInk);
    }
  }

  // The deviation plot.
  {
    const int x0 = out.plot_x0, y0 = out.plot_y0, x1 = out.plot_x1, y1 = out.plot_y1;
    detail::draw_text(img, x0, y0 - 5,
                      zero_bound ? "C(t) \xE2\x88\x92 D per axis (bound 0: interpolation)"
                                 : "(C(t) \xE2\x88\x92 D) / bound per axis",
                      kInk, Weight::kBold);
    const int gx0 = x0 + 44, gx1 = x1 - 10, gy0 = y0 + 8, gy1 = y1 - lh - 10;
    double ymax = 1.2;
    for (const Point& r : rel) ymax = std::max(ymax, 1.05 * r.cwiseAbs().maxCoeff());
    if (zero_bound) ymax = 1.1;
    const int pw = gx1 - gx0, ph = gy1 - gy0;
    detail::ColorBuffer cb(pw * SS, ph * SS, Vector3f::Ones());
    const std::size_t n = points.size();
    auto at = [&](double j, double y) {
      const double fx = n > 1 ? j / (n - 1) : 0.5;
      return Vector3d(fx * (pw - 1) * SS + 0.5 * SS, (0.5 - 0.5 * y / ymax) * ph * SS, 0.0);
    };
    const detail::DepthTest none{};
    detail::draw_segment(cb, at(0, 0), at(n - 1, 0), 0.5 * SS, Vector3f::Constant(0.5f), none);
    if (!zero_bound)
      for (double yl : {-1.0, 1.0})
        detail::draw_segment(cb, at(0, yl), at(n - 1, yl), 0.9 * SS, {0.95f, 0.55f, 0.10f}, none);
    for (int a = 0; a < 3; ++a) {
      for (std::size_t j = 0; j + 1 < n; ++j)
        detail::draw_segment(cb, at(j, rel[j][a]), at(j + 1, rel[j + 1][a]), 0.5 * SS,
                             kAxisColour[a], none);
      if (n <= 400)
        for (std::size_t j = 0; j < n; ++j)
          detail::draw_disc(cb, at(j, rel[j][a]), 1.6 * SS, kAxisColour[a], none);
    }
    blit(img, detail::downsample(cb, SS), gx0, gy0);
    frame(img, gx0 - 1, gy0 - 1, gx1 + 1, gy1 + 1, {170, 170, 170});
    auto ytick = [&](double y, const std::string& label) {
      const int py = gy0 + static_cast<int>(std::lround((0.5 - 0.5 * y / ymax) * ph));
      detail::fill_rect(img, gx0 - 4, py, gx0 - 1, py + 1, kInk);
      detail::draw_text(img, gx0 - 6, py + detail::ascent() / 2 - 1, label, kInk, Weight::kRegular,
                        Align::kRight);
    };
    ytick(0, "0");
    if (zero_bound) {
      ytick(1, detail::format_g(abs_scale, 2));
      ytick(-1, detail::format_g(-abs_scale, 2));
    } else {
      ytick(1, "+1");
      ytick(-1, detail::format_g(-1));
    }
    detail::draw_text(img, gx0, gy1 + lh + 4, "point 0", kInk);
    detail::draw_text(img, gx1, gy1 + lh + 4, "point " + std::to_string(n - 1), kInk,
                      Weight::kRegular, Align::kRight);
    int lx = (gx0 + gx1) / 2 - 30;
    for (int a = 0; a < 3; ++a)
      lx = detail::draw_text(img, lx, gy1 + lh + 4, std::string(1, "xyz"[a]),
                             detail::to_rgb(kAxisColour[a]), Weight::kBold) +
           10;
  }
  out.image = std::move(img);
  return out;
}

}  // namespace sfit::render
