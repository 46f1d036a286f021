#include "surface_overlays.h"

#include <algorithm>
#include <cmath>

#include "surface_deviation.h"

namespace sfit::render::detail {

namespace {

using Eigen::Vector3d;
using Eigen::Vector3f;

// The surface's v-isocurves at the rows' v, 2 segments a tessellation quad along u.
void draw_rows(ColorBuffer& cb, const Scene& sc, const SurfaceView& view, const DepthTest& t) {
  const Surface& s = view.s;
  const double ue = s.u_end(), px = view.ss;
  const Vector3f blue(0.08f, 0.22f, 0.60f);
  const int n = 2 * view.nu;
  for (double v : sc.row_v) {
    Vector3d prev = view.to_samples(s.evaluate(0, v));
    for (int i = 1; i <= n; ++i) {
      const Vector3d q = view.to_samples(s.evaluate(ue * i / n, v));
      draw_segment(cb, prev, q, 0.75 * px, blue, t);
      prev = q;
    }
  }
}

// The control net: its edges (a closed direction's wrapping too) and its points.
void draw_net(ColorBuffer& cb, const SurfaceView& view, const DepthTest& t) {
  const Surface& s = view.s;
  const double px = view.ss;
  const Vector3f red(0.78f, 0.12f, 0.08f);
  const int fu = s.periodic_u ? s.count_u : s.count_u - 1,
            fv = s.periodic_v ? s.count_v : s.count_v - 1;
  for (int i = 0; i < s.count_u; ++i)
    for (int j = 0; j < s.count_v; ++j) {
      const Vector3d a = view.to_samples(s.at(i, j));
      if (i < fu)
        draw_segment(cb, a, view.to_samples(s.at((i + 1) % s.count_u, j)), 0.6 * px, red, t);
      if (j < fv)
        draw_segment(cb, a, view.to_samples(s.at(i, (j + 1) % s.count_v)), 0.6 * px, red, t);
    }
  for (const Point& p : s.control) draw_disc(cb, view.to_samples(p), 1.8 * px, red, t);
}

}  // namespace

double point_radius(const RenderResult& res, std::size_t n_points) {
  const double plot_area =
      static_cast<double>(res.plot_x1 - res.plot_x0) * (res.plot_y1 - res.plot_y0);
  return n_points
             ? std::clamp(0.22 * std::sqrt(plot_area / static_cast<double>(n_points)), 1.6, 4.0)
             : 2;
}

void draw_overlays(ColorBuffer& cb, const Scene& sc, const RenderOptions& o,
                   const SurfaceView& view, const SurfaceRaster& r,
                   const std::vector<double>& ratio, RenderResult& res) {
  if (o.rows) draw_rows(cb, sc, view, DepthTest{&r.g, r.slack, 0.f});
  if (o.net) draw_net(cb, view, DepthTest{&r.g, r.slack, 0.3f});
  const double radius = point_radius(res, sc.rows ? sc.rows->total_points() : 0);
  if (o.mode == Mode::kDeviation) {
    draw_deviation_points(cb, sc, view, r, ratio, radius, res);
  } else if (o.points) {
    const DepthTest t{&r.g, r.slack, 0.f};
    for (const Point& p : sc.rows->points())
      draw_disc(cb, view.to_samples(view.cam.exaggerate(p)), std::min(radius, 2.2) * view.ss,
                Vector3f(0.1f, 0.1f, 0.1f), t);
  }
}

}  // namespace sfit::render::detail
