// The surface picture's raster (surface_picture.h): the surface tessellated at the view's
// counts and rasterised into a depth buffer of its (u, v) per sample, tinted in the deviation
// mode by the ratio of the data point nearest each vertex. Private to the surface picture.
#pragma once

#include <vector>

#include "raster.h"
#include "sfit/render/surface_picture.h"
#include "surface_view.h"

namespace sfit::render::detail {

struct SurfaceRaster {
  GBuffer g;     ///< the samples the surface covers, with their depth, (u, v) and tint
  double slack;  ///< the depth slack of overlays (a fraction of the scene's extent)
};

/// The surface rasterised at o.width x o.height pixels of view.ss x view.ss samples. `ratio`:
/// each data point's |d| / T (deviation_ratios()), empty for no tint. Of res: the plot area.
SurfaceRaster raster_surface(const Scene& sc, const RenderOptions& o, const SurfaceView& view,
                             const std::vector<double>& ratio, const RenderResult& res);

}  // namespace sfit::render::detail
