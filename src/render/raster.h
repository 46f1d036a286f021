// The software rasteriser: a depth buffer that records the surface parameters (u, v) seen at
// each sample, a colour buffer, triangles, lines and discs, and the box filter to the final
// picture. Coordinates are in samples (supersampled pixels), y downwards; depth grows towards
// the viewer.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "sfit/render/image.h"

namespace sfit::render::detail {

/// A screen vertex: x, y in samples, depth; the surface parameters and one more value
/// (the deviation mode's tint) carried along.
struct ScreenVertex {
  double x, y, depth;
  double u, v;
  double attr = 0;
};

/// What the surface leaves at each sample: the nearest depth, its (u, v) and attribute.
struct GBuffer {
  int width = 0, height = 0;
  std::vector<float> depth, u, v, attr;
  GBuffer(int w, int h);
  static constexpr float kEmpty = -std::numeric_limits<float>::infinity();
  bool covered(std::size_t i) const { return depth[i] != kEmpty; }
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
};

/// Fills the samples whose centres (x + 1/2, y + 1/2) lie inside the triangle, with the
/// top-left rule so that triangles sharing an edge cover each sample exactly once (no gaps,
/// no double cover), keeping the nearest depth.
void rasterize_triangle(GBuffer& g, const ScreenVertex& a, const ScreenVertex& b,
                        const ScreenVertex& c);

/// Linear RGB in [0, 1] per sample.
struct ColorBuffer {
  int width = 0, height = 0;
  std::vector<Eigen::Vector3f> rgb;
  ColorBuffer(int w, int h, const Eigen::Vector3f& fill);
  Eigen::Vector3f& at(int x, int y) { return rgb[static_cast<std::size_t>(y) * width + x]; }
};

/// How an overlay meets the surface: drawn where not behind it (depth >= surface - slack),
/// blended at `hidden_alpha` where behind it (0: not drawn there).
struct DepthTest {
  const GBuffer* g = nullptr;  ///< null: no test, always drawn
  double slack = 0;
  float hidden_alpha = 0;
};

/// A segment of width 2 * half_width samples with round caps, depth interpolated.
void draw_segment(ColorBuffer& c, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                  double half_width, const Eigen::Vector3f& colour, const DepthTest& test);
/// A filled disc of `radius` samples at p (x, y, depth).
void draw_disc(ColorBuffer& c, const Eigen::Vector3d& p, double radius,
               const Eigen::Vector3f& colour, const DepthTest& test);

/// Averages factor x factor samples into one pixel (box filter) and rounds to 8 bits.
Image downsample(const ColorBuffer& c, int factor);

Eigen::Vector3f to_float(Rgb c);
Rgb to_rgb(const Eigen::Vector3f& c);

/// Fills [x0, x1) x [y0, y1) of the picture (clipped).
void fill_rect(Image& img, int x0, int y0, int x1, int y1, Rgb colour);
/// A ring of radius r and thickness t around (cx, cy) on the picture, anti-aliased.
void draw_ring(Image& img, double cx, double cy, double r, double t, Rgb colour);

}  // namespace sfit::render::detail

namespace sfit::render::detail {
/// Fills the samples whose centres lie in the convex hull of `points` (x, y in samples).
void fill_hull(ColorBuffer& c, std::vector<Eigen::Vector2d> points, const Eigen::Vector3f& colour);
/// Fills the samples of [x0, x1) x [y0, y1) (clipped) with `colour`.
void fill_box(ColorBuffer& c, double x0, double y0, double x1, double y1,
              const Eigen::Vector3f& colour);
}  // namespace sfit::render::detail
