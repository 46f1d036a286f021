// The surface picture's overlays (surface_picture.h): the row curves, the control net and the
// data points, drawn on the samples against the surface's depth. Private to the surface
// picture.
#pragma once

#include <cstddef>
#include <vector>

#include "raster.h"
#include "sfit/render/surface_picture.h"
#include "surface_raster.h"
#include "surface_view.h"

namespace sfit::render::detail {

/// The data points' disc radius in pixels: from the plot area (res.plot_*) per point, 1.6 ...
/// 4; 2 without points.
double point_radius(const RenderResult& res, std::size_t n_points);

/// The overlays the options ask for, in this order: the row curves (o.rows), the control net
/// (o.net), the data points (o.points; in the deviation mode in their colours of `ratio`,
/// draw_deviation_points(), which sets res.worst_*).
void draw_overlays(ColorBuffer& cb, const Scene& sc, const RenderOptions& o,
                   const SurfaceView& view, const SurfaceRaster& r,
                   const std::vector<double>& ratio, RenderResult& res);

}  // namespace sfit::render::detail
