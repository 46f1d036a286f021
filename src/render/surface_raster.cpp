#include "surface_raster.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "nearest.h"

namespace sfit::render::detail {

SurfaceRaster raster_surface(const Scene& sc, const RenderOptions& o, const SurfaceView& view,
                             const std::vector<double>& ratio, const RenderResult& res) {
  const Surface& s = view.s;
  const int SS = view.ss, nu = view.nu, nv = view.nv;
  const double ue = s.u_end(), ve = s.v_end();
  // The surface tinted by the ratio of the data point nearest each vertex (the points
  // themselves are drawn in exact colours).
  std::unique_ptr<NearestPoint> nearest;
  if (!ratio.empty()) {
    std::vector<Point> pe(ratio.size());
    for (std::size_t k = 0; k < ratio.size(); ++k)
      pe[k] = view.cam.exaggerate(sc.rows->points()[k]);
    nearest = std::make_unique<NearestPoint>(std::move(pe));
  }
  std::vector<ScreenVertex> vert(static_cast<std::size_t>(nu + 1) * (nv + 1));
  auto vid = [nv](int i, int j) { return static_cast<std::size_t>(i) * (nv + 1) + j; };
  double depth_lo = INFINITY, depth_hi = -INFINITY;
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      const double u = ue * i / nu, v = ve * j / nv;
      // A closed direction's last column is its first one, bit for bit: no seam can open.
      const int si = s.periodic_u && i == nu ? 0 : i;
      const int sj = s.periodic_v && j == nv ? 0 : j;
      Eigen::Vector3d q;
      double attr = 0;
      if (si != i || sj != j) {
        const auto& w = vert[vid(si, sj)];
        q = Eigen::Vector3d(w.x / SS, w.y / SS, w.depth);
        attr = w.attr;
      } else {
        const Point p = s.evaluate(u, v);
        q = view.to_screen(p);
        if (nearest) attr = ratio[nearest->nearest(p)];
      }
      vert[vid(i, j)] = {q.x() * SS, q.y() * SS, q.z(), u, v, attr};
      depth_lo = std::min(depth_lo, q.z());
      depth_hi = std::max(depth_hi, q.z());
    }
  // Unit world length in picture pixels and the depth slack of overlays.
  const double extent =
      std::max(depth_hi - depth_lo, 1e-300) +
      std::max(res.plot_x1 - res.plot_x0, res.plot_y1 - res.plot_y0) / view.cam.scale;
  SurfaceRaster r{GBuffer(o.width * SS, o.height * SS), 0.004 * extent};
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      rasterize_triangle(r.g, vert[vid(i, j)], vert[vid(i + 1, j)], vert[vid(i + 1, j + 1)]);
      rasterize_triangle(r.g, vert[vid(i, j)], vert[vid(i + 1, j + 1)], vert[vid(i, j + 1)]);
    }
  return r;
}

}  // namespace sfit::render::detail
