// The surface picture's deviation colouring (surface_picture.h, Mode::kDeviation): each data
// point's |d| / T, and the points drawn as discs in those colours over the surface, the worst
// one always shown. Private to the surface picture.
#pragma once

#include <vector>

#include "raster.h"
#include "sfit/render/surface_picture.h"
#include "surface_raster.h"
#include "surface_view.h"

namespace sfit::render::detail {

/// Each data point's |d| / T (tolerance_ratio()) in the deviation mode; empty otherwise or
/// without points.
std::vector<double> deviation_ratios(const Scene& sc, const RenderOptions& o);

/// The data points as discs of `radius` pixels coloured by `ratio` (deviation_ratios()),
/// the lowest first so that the worst lie on top, with a dark rim where they are sparse; the
/// worst one drawn again unhidden. Sets res.worst_point and res.worst_ratio.
void draw_deviation_points(ColorBuffer& cb, const Scene& sc, const SurfaceView& view,
                           const SurfaceRaster& r, const std::vector<double>& ratio, double radius,
                           RenderResult& res);

}  // namespace sfit::render::detail
