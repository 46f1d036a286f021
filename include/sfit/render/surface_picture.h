// Pictures of a fitted surface (docs/pictures.md): lit and shaded, highlight
// stripes, deviation of the data, Gaussian and mean curvature; with the control net, the data
// points and the row curves drawn over it. Software rasterised, headless.
#pragma once

#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "sfit/render/image.h"
#include "sfit/render/view.h"
#include "sfit/rows.h"
#include "sfit/surface.h"

namespace sfit::render {

enum class Mode {
  kShaded,     ///< lit, smooth-shaded (exact normals at every sample)
  kZebra,      ///< highlight stripes (Beier and Chen 1994): a plane gives straight parallel
               ///< stripes; a kink in the stripes is a kink of the surface, a sudden bend
               ///< a jump of curvature
  kDeviation,  ///< the data points coloured by deviation relative to the tolerance
  kGauss,      ///< Gaussian curvature K = (LN - M^2) / (EG - F^2), diverging colours
  kMean,       ///< mean curvature H = (EN - 2FM + GL) / (2 (EG - F^2)), normal S_u x S_v
};

/// "shaded", "zebra", "deviation", "gauss", "mean"; throws Error(kUsage) naming `option`.
Mode parse_mode(const std::string& text, const std::string& option);
const char* to_string(Mode mode);

struct RenderOptions {
  Mode mode = Mode::kShaded;
  int width = 640, height = 480;  ///< picture size in pixels, 64 ... 4096
  View view;
  double exaggeration = 1.0;  ///< scale of the up axis (terrain relief), > 0
  bool net = false;           ///< control net (hidden parts faint)
  bool points = false;        ///< data points (needs Scene::rows)
  bool rows = false;          ///< the surface's v-isocurves at the rows (needs Scene::row_v)
  int supersample = 3;        ///< samples per pixel in x and y (anti-aliasing), 1 ... 4; fewer past
                              ///< 12 million samples (about 48 bytes each)
  double stripes = 14;        ///< zebra: stripe pairs across the surface
  double stripe_angle = NAN;  ///< zebra: the light lines' angle from the vertical in
                              ///< degrees, clockwise; NaN: along the surface's long axis
  double curvature_scale = 0;      ///< colour-bar half range for gauss/mean; 0: automatic
  std::vector<std::string> title;  ///< lines printed at the top (UTF-8)
};

/// What to draw. `surface` is required; the rest is optional and used by the modes/overlays
/// that need it.
struct Scene {
  const Surface* surface = nullptr;
  const Rows* rows = nullptr;         ///< data points
  std::span<const Point> deviations;  ///< S - D per data point (deviation mode)
  Point tolerance = Point::Zero();    ///< T for the deviation colours
  double zero_scale = 0;              ///< colour scale of axes with T = 0 (see tolerance_ratio)
  std::span<const double> row_v;      ///< v of each row (rows overlay)
  std::string deviation_note;         ///< how the deviations were measured (printed)
};

struct RenderResult {
  Image image;
  Camera camera;  ///< projects world points to picture pixels
  int plot_x0 = 0, plot_y0 = 0, plot_x1 = 0, plot_y1 = 0;  ///< the drawing area
  int bar_x0 = 0, bar_y0 = 0, bar_x1 = 0, bar_y1 = 0;      ///< colour bar (empty if none)
  double scale = 0;  ///< colour-bar half range (gauss/mean) or 1 (deviation, in T)
  double value_min = 0, value_max = 0;  ///< curvature seen over the visible surface
  double stripe_angle = 0;  ///< zebra: the light lines' angle used (degrees from vertical)
  long worst_point = -1;    ///< deviation: index in rows.points() of the largest ratio
  double worst_ratio = 0;   ///< its |deviation| / T (per-axis maximum)
  int supersample = 1;      ///< samples per pixel in x and y used
  double seconds = 0;
};

/// Renders the scene. Throws Error(kUsage) for options out of range (naming the field, e.g.
/// "width") or a mode/overlay whose data the scene lacks.
RenderResult render_surface(const Scene& scene, const RenderOptions& options);

}  // namespace sfit::render
