// The picture options shared by 'sfit render', 'sfit render-rows' and 'sfit fit --png': their
// command-line form, their checks, and the pictures of a fit.
#include "picture_options.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>

#include "cli_common.h"
#include "sfit/error.h"
#include "sfit/io/atomic_file.h"
#include "sfit/render/deviations.h"

namespace sfit::cli {
std::string format_number(double x) {
  return fmt::format("{:.4g}", x);
}
std::string format_point(const Point& p) {
  if (p.x() == p.y() && p.y() == p.z()) return format_number(p.x());
  return fmt::format("({}, {}, {})", format_number(p.x()), format_number(p.y()),
                     format_number(p.z()));
}
std::string display_name(const std::string& path) {
  return path == "-" ? std::string("standard input")
                     : std::filesystem::path(path).filename().string();
}

// "WxH" -> (W, H), each 64 ... 4096.
std::pair<int, int> parse_picture_size(const std::string& text, const std::string& option,
                                       int min) {
  const auto x = text.find_first_of("xX");
  int w = 0, h = 0;
  auto number = [](std::string_view s, int& v) {
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    return !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
  };
  if (x == std::string::npos || !number(std::string_view(text).substr(0, x), w) ||
      !number(std::string_view(text).substr(x + 1), h))
    throw Error(ErrorCode::kUsage, "'" + text + "' is not a size WIDTHxHEIGHT, e.g. 640x480",
                Place{.option = option});
  if (w < min || h < min || w > 4096 || h > 4096)
    throw Error(ErrorCode::kUsage,
                fmt::format("size {}x{} is out of range {} ... 4096 each way", w, h, min),
                Place{.option = option}, {static_cast<double>(w), static_cast<double>(h)});
  return {w, h};
}

namespace {

int parse_up(const std::string& text) {
  if (text == "x" || text == "X") return 0;
  if (text == "y" || text == "Y") return 1;
  if (text == "z" || text == "Z") return 2;
  throw Error(ErrorCode::kUsage, "'" + text + "' is not an axis: give x, y or z",
              Place{.option = "--up"});
}

void check_png_path(const std::string& path, const std::string& option) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".png")
    throw Error(ErrorCode::kUsage, "'" + path + "': a picture is written as .png",
                Place{.option = option});
  io::check_writable(path);
}

}  // namespace

std::string describe_surface(const Surface& s, std::size_t points, std::size_t rows,
                             const Point* tol, const PictureArgs& a) {
  std::string t;
  if (points) t = fmt::format("{} points in {} rows \xC2\xB7 ", points, rows);
  t += fmt::format("{} \xC3\x97 {} control points, degree {} \xC3\x97 {}", s.count_u, s.count_v,
                   s.degree_u, s.degree_v);
  if (s.periodic_u || s.periodic_v)
    t += s.periodic_u && s.periodic_v ? ", closed u, v"
         : s.periodic_u               ? ", closed u"
                                      : ", closed v";
  if (tol) t += " \xC2\xB7 T = " + format_point(*tol);
  t += " \xC2\xB7 view " + a.view;
  return t;
}

void add_picture_options(CLI::App* c, PictureArgs& a, const std::string& group,
                         CLI::Option* needs) {
  std::vector<CLI::Option*> opts;
  opts.push_back(
      c->add_option("--mode", a.modes,
                    "shaded (default), zebra (highlight stripes), deviation (data points "
                    "coloured by |d|/T), gauss or mean (curvature)"));
  opts.push_back(c->add_option("--view", a.view,
                               "iso (default), front, top, side, or AZIMUTH,ELEVATION in degrees"));
  opts.push_back(
      c->add_option("--up", a.up, "the axis pointing up in the picture: x, y or z (default)"));
  opts.push_back(c->add_option("--size", a.size, "picture size WIDTHxHEIGHT (default 640x480)"));
  opts.push_back(c->add_option("--exaggerate", a.exaggerate,
                               "scale of the up axis, e.g. 5 for terrain relief"));
  opts.push_back(c->add_flag("--net", a.net, "draw the control net (hidden parts faint)"));
  opts.push_back(c->add_flag("--points", a.points, "draw the data points"));
  opts.push_back(
      c->add_flag("--rows", a.rows, "draw the row curves (the surface's v-isocurves at the rows)"));
  opts.push_back(
      c->add_option("--stripes", a.stripes, "zebra: stripe pairs across the surface (default 14)"));
  opts.push_back(c->add_option("--stripe-angle", a.stripe_angle,
                               "zebra: the light lines' angle from the vertical in degrees "
                               "(default: along the surface's long axis)"));
  opts.push_back(
      c->add_option("--curvature-scale", a.curvature_scale,
                    "gauss/mean: the colour bar's half range (default: 95th percentile)"));
  opts.push_back(
      c->add_option("--title", a.title, "first title line (default: file name and mode)"));
  for (CLI::Option* o : opts) {
    o->group(group);
    if (needs) o->needs(needs);
  }
}

void check_picture_outputs(const std::vector<std::string>& pngs, const PictureArgs& a,
                           const std::string& option) {
  for (const auto& p : pngs) check_png_path(p, option);
  for (const auto& m : a.modes) render::parse_mode(m, "--mode");
  if (!pngs.empty() && a.modes.size() > 1 && a.modes.size() != pngs.size())
    throw Error(ErrorCode::kUsage,
                fmt::format("{} modes for {} pictures: give one --mode, or one per picture",
                            a.modes.size(), pngs.size()),
                Place{.option = "--mode"});
  picture_options(a, render::Mode::kShaded);  // checks the rest
}

render::RenderOptions picture_options(const PictureArgs& a, render::Mode mode) {
  render::RenderOptions o;
  o.mode = mode;
  const auto [w, h] = parse_picture_size(a.size, "--size", 64);
  o.width = w;
  o.height = h;
  o.view = render::parse_view(a.view, parse_up(a.up), "--view");
  if (!(a.exaggerate > 0) || !std::isfinite(a.exaggerate))
    throw Error(ErrorCode::kUsage, "must be a finite number > 0", Place{.option = "--exaggerate"},
                {a.exaggerate});
  o.exaggeration = a.exaggerate;
  if (!(a.stripes > 0) || a.stripes > 1000)
    throw Error(ErrorCode::kUsage, "must be > 0 and <= 1000", Place{.option = "--stripes"},
                {a.stripes});
  o.stripes = a.stripes;
  if (!std::isnan(a.stripe_angle) && !std::isfinite(a.stripe_angle))
    throw Error(ErrorCode::kUsage, "must be a finite angle in degrees",
                Place{.option = "--stripe-angle"}, {a.stripe_angle});
  o.stripe_angle = a.stripe_angle;
  if (!(a.curvature_scale >= 0) || !std::isfinite(a.curvature_scale))
    throw Error(ErrorCode::kUsage, "must be a finite number >= 0 (0: automatic)",
                Place{.option = "--curvature-scale"}, {a.curvature_scale});
  o.curvature_scale = a.curvature_scale;
  o.net = a.net;
  o.points = a.points;
  o.rows = a.rows;
  return o;
}

void write_fit_pictures(const std::vector<std::string>& pngs, const PictureArgs& a,
                        const FitResult& fit, const Rows& rows, const std::string& input_name) {
  if (pngs.empty()) return;
  const std::vector<Point> deviations =
      render::deviations_at_parameters(fit.surface, rows, fit.u, fit.v_for_points());
  double largest = 0;
  for (const Point& d : deviations) largest = std::max(largest, d.cwiseAbs().maxCoeff());
  for (std::size_t i = 0; i < pngs.size(); ++i) {
    const std::string m = a.modes.empty()       ? "shaded"
                          : a.modes.size() == 1 ? a.modes[0]
                                                : a.modes[i];
    const render::Mode mode = render::parse_mode(m, "--mode");
    render::Scene scene;
    scene.surface = &fit.surface;
    scene.rows = &rows;
    scene.deviations = deviations;
    scene.tolerance = fit.report.tolerance;
    scene.zero_scale = largest > 0 ? largest : 1;
    scene.row_v = fit.v;
    scene.deviation_note = "at the fitted parameters, as the report";
    render::RenderOptions o = picture_options(a, mode);
    o.title = {
        a.title.empty() ? fmt::format("{} \xC2\xB7 {}", display_name(input_name), m) : a.title,
        describe_surface(fit.surface, rows.total_points(), rows.size(), &fit.report.tolerance, a)};
    const render::RenderResult r = render::render_surface(scene, o);
    if (mode == render::Mode::kDeviation && r.worst_point >= 0) {
      const Eigen::Vector3d px = r.camera.project(rows.points()[r.worst_point]);
      say(fmt::format(
          "deviation picture: max |d|/T {} at point {} of the input, pixel ({:.0f}, {:.0f})",
          format_number(r.worst_ratio), r.worst_point, px.x(), px.y()));
    }
    render::write_png(pngs[i], r.image);  // held back until every output is written
    say(fmt::format("drew {} ({}x{}, {} mode, {:.2f} s)", pngs[i], r.image.width, r.image.height, m,
                    r.seconds));
  }
}

}  // namespace sfit::cli
