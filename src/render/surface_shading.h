// The surface picture's colours (surface_picture.h): at every sample the surface covers, the
// exact normal and, by the mode, the curvature or the highlight-line coordinate from the
// surface's derivatives at the sample's (u, v); then the colour of the mode, lit by a key and a
// fill light. Private to the surface picture.
#pragma once

#include "raster.h"
#include "sfit/render/surface_picture.h"
#include "surface_view.h"

namespace sfit::render::detail {

/// The colour buffer of the surface (the background where `g` is not covered). Sets
/// res.stripe_angle, and res.scale (gauss and mean: with res.value_min and res.value_max;
/// deviation: 1).
ColorBuffer shade_surface(const RenderOptions& o, const SurfaceView& view, const GBuffer& g,
                          RenderResult& res);

}  // namespace sfit::render::detail
