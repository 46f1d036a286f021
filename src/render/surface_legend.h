// The surface picture's text and colour bar (surface_picture.h): where the title, the colour
// bar and the notes go on the picture, and drawing them on the finished picture, with the ring
// around the worst point of the deviation mode. Private to the surface picture.
#pragma once

#include "sfit/render/surface_picture.h"

namespace sfit::render::detail {

/// Where the picture's parts go: the title at the top (a line each), a colour bar on the right
/// (deviation, gauss and mean) and the notes at the bottom (every mode but shaded); the
/// surface gets the rest (RenderResult's plot_*).
struct Layout {
  bool has_bar = false;
  int line_h = 0;  ///< one line of text
  int title_h = 0, footer_h = 0, bar_w = 0;
};
Layout layout_of(const RenderOptions& o);

/// On the downsampled picture: the ring around res.worst_point (of res.camera's view, at the
/// points' disc `radius` in pixels), the title, the colour bar (sets res.bar_*; of res.scale
/// and res.worst_ratio) and the notes at the bottom.
void draw_legend(Image& img, const Scene& sc, const RenderOptions& o, const Layout& lay,
                 double radius, RenderResult& res);

}  // namespace sfit::render::detail
