#include "raster.h"

#include <algorithm>
#include <cmath>

namespace sfit::render::detail {

GBuffer::GBuffer(int w, int h)
    : width(w),
      height(h),
      depth(static_cast<std::size_t>(w) * h, kEmpty),
      u(static_cast<std::size_t>(w) * h, 0.f),
      v(static_cast<std::size_t>(w) * h, 0.f),
      attr(static_cast<std::size_t>(w) * h, 0.f) {}

namespace {

double edge(const ScreenVertex& a, const ScreenVertex& b, double x, double y) {
  return (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
}

// Top-left rule for a counter-clockwise triangle in y-down coordinates (positive area):
// a sample exactly on an edge belongs to the triangle if the edge is a top or a left edge.
bool top_left(const ScreenVertex& a, const ScreenVertex& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  return (dy == 0 && dx < 0) || dy > 0;
}

}  // namespace

void rasterize_triangle(GBuffer& g, const ScreenVertex& a0, const ScreenVertex& b0,
                        const ScreenVertex& c0) {
  ScreenVertex a = a0, b = b0, c = c0;
  double area = edge(a, b, c.x, c.y);
  if (area == 0 || !std::isfinite(area)) return;
  if (area < 0) {
    std::swap(b, c);
    area = -area;
  }
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
  const int x1 = std::min(g.width - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
  const int y1 = std::min(g.height - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
  const bool tl_bc = top_left(b, c), tl_ca = top_left(c, a), tl_ab = top_left(a, b);
  for (int y = y0; y <= y1; ++y) {
    const double py = y + 0.5;
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5;
      const double wa = edge(b, c, px, py), wb = edge(c, a, px, py), wc = edge(a, b, px, py);
      if (wa < 0 || wb < 0 || wc < 0) continue;
      if ((wa == 0 && !tl_bc) || (wb == 0 && !tl_ca) || (wc == 0 && !tl_ab)) continue;
      const double la = wa / area, lb = wb / area, lc = 1.0 - la - lb;
      const float d = static_cast<float>(la * a.depth + lb * b.depth + lc * c.depth);
      const std::size_t i = g.index(x, y);
      if (d <= g.depth[i]) continue;
      g.depth[i] = d;
      g.u[i] = static_cast<float>(la * a.u + lb * b.u + lc * c.u);
      g.v[i] = static_cast<float>(la * a.v + lb * b.v + lc * c.v);
      g.attr[i] = static_cast<float>(la * a.attr + lb * b.attr + lc * c.attr);
    }
  }
}

ColorBuffer::ColorBuffer(int w, int h, const Eigen::Vector3f& fill)
    : width(w), height(h), rgb(static_cast<std::size_t>(w) * h, fill) {}

namespace {

// Blends `colour` into sample (x, y) if the depth test lets it through.
void plot(ColorBuffer& c, int x, int y, double depth, const Eigen::Vector3f& colour,
          const DepthTest& t) {
  float alpha = 1.f;
  if (t.g) {
    const std::size_t i = t.g->index(x, y);
    if (t.g->covered(i) && depth < t.g->depth[i] - t.slack) alpha = t.hidden_alpha;
  }
  if (alpha <= 0) return;
  Eigen::Vector3f& p = c.at(x, y);
  p = alpha * colour + (1 - alpha) * p;
}

}  // namespace

void draw_segment(ColorBuffer& c, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, double hw,
                  const Eigen::Vector3f& colour, const DepthTest& t) {
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min(p0.x(), p1.x()) - hw)));
  const int x1 = std::min(c.width - 1, static_cast<int>(std::ceil(std::max(p0.x(), p1.x()) + hw)));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min(p0.y(), p1.y()) - hw)));
  const int y1 = std::min(c.height - 1, static_cast<int>(std::ceil(std::max(p0.y(), p1.y()) + hw)));
  const Eigen::Vector2d a = p0.head<2>(), d = p1.head<2>() - a;
  const double len2 = d.squaredNorm();
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const Eigen::Vector2d q(x + 0.5, y + 0.5);
      const double s = len2 > 0 ? std::clamp((q - a).dot(d) / len2, 0.0, 1.0) : 0.0;
      if ((a + s * d - q).squaredNorm() > hw * hw) continue;
      plot(c, x, y, p0.z() + s * (p1.z() - p0.z()), colour, t);
    }
}

void draw_disc(ColorBuffer& c, const Eigen::Vector3d& p, double r, const Eigen::Vector3f& colour,
               const DepthTest& t) {
  draw_segment(c, p, p, r, colour, t);
}

Image downsample(const ColorBuffer& c, int f) {
  Image img(c.width / f, c.height / f);
  const float n = static_cast<float>(f * f);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      Eigen::Vector3f s = Eigen::Vector3f::Zero();
      for (int j = 0; j < f; ++j)
        for (int i = 0; i < f; ++i)
          s += c.rgb[static_cast<std::size_t>(y * f + j) * c.width + x * f + i];
      img.set(x, y, to_rgb(s / n));
    }
  return img;
}

Eigen::Vector3f to_float(Rgb c) {
  return Eigen::Vector3f(c.r, c.g, c.b) / 255.f;
}

Rgb to_rgb(const Eigen::Vector3f& c) {
  auto q = [](float x) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.f, 1.f) * 255.f));
  };
  return {q(c.x()), q(c.y()), q(c.z())};
}

void fill_rect(Image& img, int x0, int y0, int x1, int y1, Rgb colour) {
  for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x) img.set(x, y, colour);
}

void draw_ring(Image& img, double cx, double cy, double r, double t, Rgb colour) {
  const int x0 = static_cast<int>(std::floor(cx - r - t)),
            x1 = static_cast<int>(std::ceil(cx + r + t));
  const int y0 = static_cast<int>(std::floor(cy - r - t)),
            y1 = static_cast<int>(std::ceil(cy + r + t));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      if (!img.contains(x, y)) continue;
      const double d = std::abs(std::hypot(x + 0.5 - cx, y + 0.5 - cy) - r);
      const double a = std::clamp(t / 2 + 0.5 - d, 0.0, 1.0);
      if (a <= 0) continue;
      const Rgb o = img.at(x, y);
      auto mix = [a](std::uint8_t bg, std::uint8_t fg) {
        return static_cast<std::uint8_t>(std::lround(bg + a * (static_cast<double>(fg) - bg)));
      };
      img.set(x, y, {mix(o.r, colour.r), mix(o.g, colour.g), mix(o.b, colour.b)});
    }
}

}  // namespace sfit::render::detail

namespace sfit::render::detail {
void fill_box(ColorBuffer& c, double x0, double y0, double x1, double y1,
              const Eigen::Vector3f& colour) {
  const int a = std::max(0, static_cast<int>(std::floor(x0))),
            b = std::min(c.width, static_cast<int>(std::ceil(x1)));
  const int d = std::max(0, static_cast<int>(std::floor(y0))),
            e = std::min(c.height, static_cast<int>(std::ceil(y1)));
  for (int y = d; y < e; ++y)
    for (int x = a; x < b; ++x) c.at(x, y) = colour;
}
}  // namespace sfit::render::detail

namespace sfit::render::detail {
void fill_hull(ColorBuffer& c, std::vector<Eigen::Vector2d> pts, const Eigen::Vector3f& colour) {
  if (pts.empty()) return;
  // Andrew's monotone chain: the hull counter-clockwise (in y-down coordinates: clockwise).
  std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  h.resize(k > 1 ? k - 1 : k);
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const auto& p : h) {
    x0 = std::min(x0, p.x());
    x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y());
    y1 = std::max(y1, p.y());
  }
  const int a = std::max(0, static_cast<int>(std::floor(x0))),
            b = std::min(c.width - 1, static_cast<int>(std::ceil(x1)));
  const int d = std::max(0, static_cast<int>(std::floor(y0))),
            e = std::min(c.height - 1, static_cast<int>(std::ceil(y1)));
  for (int y = d; y <= e; ++y)
    for (int x = a; x <= b; ++x) {
      const Eigen::Vector2d q(x + 0.5, y + 0.5);
      bool inside = true;
      for (std::size_t i = 0; i < h.size() && inside; ++i)
        inside = h.size() < 3 ? false : cross(h[i], h[(i + 1) % h.size()], q) >= 0;
      if (inside) c.at(x, y) = colour;
    }
}
}  // namespace sfit::render::detail
