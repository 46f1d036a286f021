#include "surface_view.h"

#include <algorithm>
#include <cmath>

namespace sfit::render::detail {

namespace {

// The tessellation's quads along u and v: an edge spans about 3 pixels on the picture, at
// least the coarse grid's cu x cv, at most 1200 each.
void tessellate(SurfaceView& view, int cu, int cv) {
  const auto& fp = view.fit_points;
  double len_u = 0, len_v = 0;
  for (int j = 0; j <= cv; ++j) {
    double l = 0;
    for (int i = 0; i < cu; ++i)
      l += (view.to_screen(fp[(i + 1) * (cv + 1) + j]) - view.to_screen(fp[i * (cv + 1) + j]))
               .head<2>()
               .norm();
    len_u = std::max(len_u, l);
  }
  for (int i = 0; i <= cu; ++i) {
    double l = 0;
    for (int j = 0; j < cv; ++j)
      l += (view.to_screen(fp[i * (cv + 1) + j + 1]) - view.to_screen(fp[i * (cv + 1) + j]))
               .head<2>()
               .norm();
    len_v = std::max(len_v, l);
  }
  view.nu = std::clamp(static_cast<int>(std::ceil(len_u / 3)), cu, 1200);
  view.nv = std::clamp(static_cast<int>(std::ceil(len_v / 3)), cv, 1200);
}

}  // namespace

Eigen::Vector3d SurfaceView::to_screen(const Point& pe) const {
  return Eigen::Vector3d(cam.origin.x() + cam.scale * pe.dot(cam.right),
                         cam.origin.y() - cam.scale * pe.dot(cam.up), pe.dot(cam.toward));
}

Eigen::Vector3d SurfaceView::to_samples(const Point& pe) const {
  Eigen::Vector3d q = to_screen(pe);
  q.x() *= ss;
  q.y() *= ss;
  return q;
}

SurfaceView set_up_view(const Scene& sc, const RenderOptions& o, const Layout& lay,
                        RenderResult& res) {
  SurfaceView view;
  const int W = o.width, H = o.height;
  view.ss = std::clamp(static_cast<int>(std::sqrt(12e6 / (static_cast<double>(W) * H))), 1,
                       o.supersample);
  res.supersample = view.ss;
  // B-splines are affine invariant: scaling the control points scales the surface.
  view.s = *sc.surface;
  for (Point& p : view.s.control) p[o.view.up_axis] *= o.exaggeration;
  view.cam = Camera::looking(o.view, o.exaggeration);
  res.plot_x0 = 0;
  res.plot_y0 = lay.title_h;
  res.plot_x1 = W - lay.bar_w;
  res.plot_y1 = H - lay.footer_h;

  // A coarse grid of the surface (4 samples a knot span at least) fits the camera.
  const Surface& s = view.s;
  const double ue = s.u_end(), ve = s.v_end();
  const int cu = std::clamp(4 * static_cast<int>(std::ceil(ue)), 24, 256);
  const int cv = std::clamp(4 * static_cast<int>(std::ceil(ve)), 24, 256);
  std::vector<Point>& fit_points = view.fit_points;
  fit_points.reserve(static_cast<std::size_t>(cu + 1) * (cv + 1));
  for (int i = 0; i <= cu; ++i)
    for (int j = 0; j <= cv; ++j) fit_points.push_back(s.evaluate(ue * i / cu, ve * j / cv));
  view.n_surface_fit = fit_points.size();
  if (o.net)
    for (const Point& p : s.control) fit_points.push_back(p);
  if (o.points || o.mode == Mode::kDeviation)
    for (const Point& p : sc.rows->points()) fit_points.push_back(view.cam.exaggerate(p));
  view.cam.fit(fit_points, res.plot_x0, res.plot_y0, res.plot_x1, res.plot_y1, 0.04);
  tessellate(view, cu, cv);
  return view;
}

}  // namespace sfit::render::detail
