// The surface picture's view (surface_picture.h): the surface with its up axis exaggerated,
// the camera fitted to the plot area, the samples per pixel, and a tessellation fine enough for
// the picture. Private to the surface picture.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "sfit/render/surface_picture.h"
#include "surface_legend.h"

namespace sfit::render::detail {

struct SurfaceView {
  Surface s;   ///< the surface in exaggerated coordinates
  Camera cam;  ///< fitted to the plot area
  int ss = 1;  ///< samples per pixel in x and y
  /// What the camera was fitted to (exaggerated): first a coarse grid of the surface (4
  /// samples a knot span at least), then the control points (net) and the data points (points,
  /// deviation).
  std::vector<Point> fit_points;
  std::size_t n_surface_fit = 0;  ///< the coarse grid's share of fit_points
  int nu = 0, nv = 0;             ///< the tessellation's quads along u and v

  /// An exaggerated point's picture position (x, y) in pixels and its depth.
  Eigen::Vector3d to_screen(const Point& pe) const;
  /// The same with x and y in samples.
  Eigen::Vector3d to_samples(const Point& pe) const;
};

/// The view of the scene: sets res.supersample and the plot area (res.plot_*, the picture
/// less the `lay`'s title, bar and notes). Samples cost about 48 bytes each: past some 12
/// million, fewer samples per pixel than o.supersample.
SurfaceView set_up_view(const Scene& sc, const RenderOptions& o, const Layout& lay,
                        RenderResult& res);

}  // namespace sfit::render::detail
