// The surface picture (surface_picture.h) by its steps, each in its own file: the view
// (surface_view.h: layout, camera, tessellation), the raster (surface_raster.h), the colours of
// the mode (surface_shading.h), the overlays (surface_overlays.h; the deviation mode's points:
// surface_deviation.h), and the text and colour bar (surface_legend.h).
#include "sfit/render/surface_picture.h"

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "raster.h"
#include "sfit/error.h"
#include "surface_deviation.h"
#include "surface_legend.h"
#include "surface_overlays.h"
#include "surface_raster.h"
#include "surface_shading.h"
#include "surface_view.h"

namespace sfit::render {

Mode parse_mode(const std::string& text, const std::string& option) {
  if (text == "shaded") return Mode::kShaded;
  if (text == "zebra") return Mode::kZebra;
  if (text == "deviation") return Mode::kDeviation;
  if (text == "gauss") return Mode::kGauss;
  if (text == "mean") return Mode::kMean;
  throw Error(ErrorCode::kUsage,
              "'" + text + "' is not a mode: give shaded, zebra, deviation, gauss or mean",
              Place{.option = option});
}

const char* to_string(Mode m) {
  switch (m) {
    case Mode::kShaded:
      return "shaded";
    case Mode::kZebra:
      return "zebra";
    case Mode::kDeviation:
      return "deviation";
    case Mode::kGauss:
      return "gauss";
    case Mode::kMean:
      return "mean";
  }
  return "shaded";
}

namespace {

[[noreturn]] void bad(const std::string& field, const std::string& why, double value) {
  throw Error(ErrorCode::kUsage, why, Place{.option = field}, {value});
}

void validate(const Scene& sc, const RenderOptions& o) {
  if (!sc.surface) throw Error(ErrorCode::kInternal, "render_surface: no surface");
  if (o.width < 64 || o.width > 4096) bad("width", "picture width must be 64 ... 4096", o.width);
  if (o.height < 64 || o.height > 4096)
    bad("height", "picture height must be 64 ... 4096", o.height);
  if (o.supersample < 1 || o.supersample > 4)
    bad("supersample", "supersampling must be 1 ... 4", o.supersample);
  if (!(o.exaggeration > 0) || !std::isfinite(o.exaggeration))
    bad("exaggeration", "exaggeration must be a finite number > 0", o.exaggeration);
  if (!(o.stripes > 0) || o.stripes > 1000)
    bad("stripes", "stripes must be > 0 and <= 1000", o.stripes);
  if (!(o.curvature_scale >= 0) || !std::isfinite(o.curvature_scale))
    bad("curvature_scale", "curvature scale must be a finite number >= 0", o.curvature_scale);
  // A surface of no size (one point) or beyond double's squares leaves no camera to place:
  // refuse it rather than search for a view for minutes and draw noise.
  {
    Point lo = Point::Constant(INFINITY), hi = Point::Constant(-INFINITY);
    for (const Point& p : sc.surface->control) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const double size = sc.surface->control.empty() ? 0.0 : (hi - lo).norm();
    if (!(size >= 1e-150 && size <= 1e150))
      throw Error(ErrorCode::kInputData,
                  size == 0 ? std::string("the surface is a single point: nothing to draw")
                            : "the surface's size " + std::to_string(size) +
                                  " is out of the range sfit draws (1e-150 ... 1e150)",
                  Place{}, {size});
  }
  const std::size_t n = sc.rows ? sc.rows->total_points() : 0;
  if ((o.points || o.mode == Mode::kDeviation) && !sc.rows)
    bad(o.points ? "points" : "mode", "this picture needs the data points", 0);
  if (o.mode == Mode::kDeviation && sc.deviations.size() != n)
    bad("mode", "the deviation picture needs one deviation per data point",
        static_cast<double>(sc.deviations.size()));
  if (o.rows && (!sc.rows || sc.row_v.size() != sc.rows->size()))
    bad("rows", "the row curves need the data rows and their v parameters",
        static_cast<double>(sc.row_v.size()));
  const Surface& s = *sc.surface;
  if (s.count_u < 1 || s.count_v < 1 ||
      s.control.size() != static_cast<std::size_t>(s.count_u) * s.count_v)
    throw Error(ErrorCode::kInputData, "the surface has no control points or a wrong count",
                Place{}, {static_cast<double>(s.count_u), static_cast<double>(s.count_v)});
}

// The supersampled picture: the surface rasterised, coloured by the mode, and the overlays on
// it against its depth (the raster freed on return).
detail::ColorBuffer draw_samples(const Scene& sc, const RenderOptions& o,
                                 const detail::SurfaceView& view, const std::vector<double>& ratio,
                                 RenderResult& res) {
  const detail::SurfaceRaster r = detail::raster_surface(sc, o, view, ratio, res);
  detail::ColorBuffer cb = detail::shade_surface(o, view, r.g, res);
  detail::draw_overlays(cb, sc, o, view, r, ratio, res);
  return cb;
}

}  // namespace

RenderResult render_surface(const Scene& sc, const RenderOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  validate(sc, o);
  RenderResult res;
  const detail::Layout lay = detail::layout_of(o);
  const detail::SurfaceView view = detail::set_up_view(sc, o, lay, res);
  const std::vector<double> ratio = detail::deviation_ratios(sc, o);
  const detail::ColorBuffer cb = draw_samples(sc, o, view, ratio, res);
  Image img = detail::downsample(cb, view.ss);
  res.camera = view.cam;
  const double radius = detail::point_radius(res, sc.rows ? sc.rows->total_points() : 0);
  detail::draw_legend(img, sc, o, lay, radius, res);
  res.image = std::move(img);
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace sfit::render
