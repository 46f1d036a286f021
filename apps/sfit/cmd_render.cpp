// sfit render, sfit render-rows, and the pictures of 'sfit fit --png'.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "commands.h"
#include "output_plan.h"
#include "picture_options.h"
#include "sfit/error.h"
#include "sfit/io/atomic_file.h"
#include "sfit/render/deviations.h"
#include "sfit/render/row_picture.h"
#include "sfit/render/surface_picture.h"
#include "surface_json_value.h"

namespace sfit::cli {
namespace {

std::string g(double x) {
  return fmt::format("{:.4g}", x);
}
std::string vec(const Point& p) {
  if (p.x() == p.y() && p.y() == p.z()) return g(p.x());
  return fmt::format("({}, {}, {})", g(p.x()), g(p.y()), g(p.z()));
}
std::string base_name(const std::string& path) {
  return path == "-" ? std::string("standard input")
                     : std::filesystem::path(path).filename().string();
}

// "WxH" -> (W, H), each 64 ... 4096.
std::pair<int, int> parse_size(const std::string& text, const std::string& option, int min) {
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

// The second title line: what the picture is of.
std::string describe(const Surface& s, std::size_t points, std::size_t rows, const Point* tol,
                     const PictureArgs& a) {
  std::string t;
  if (points) t = fmt::format("{} points in {} rows \xC2\xB7 ", points, rows);
  t += fmt::format("{} \xC3\x97 {} control points, degree {} \xC3\x97 {}", s.count_u, s.count_v,
                   s.degree_u, s.degree_v);
  if (s.periodic_u || s.periodic_v)
    t += s.periodic_u && s.periodic_v ? ", closed u, v"
         : s.periodic_u               ? ", closed u"
                                      : ", closed v";
  if (tol) t += " \xC2\xB7 T = " + vec(*tol);
  t += " \xC2\xB7 view " + a.view;
  return t;
}

struct RenderArgs {
  std::string surface;
  std::string data;
  std::string output;
  std::string tol;
  bool quiet = false;
  PictureArgs picture;
};

int run_render(const RenderArgs& a) {
  verbose = !a.quiet;
  if (a.output.empty())
    throw Error(ErrorCode::kUsage, "nothing to write: give -o PICTURE.png", Place{.option = "-o"});
  OutputPlan plan;
  plan.add_input(a.surface);
  plan.add_input(a.data);
  plan.add(a.output, "-o", OutputTarget::kPicture);
  check_picture_outputs({a.output}, a.picture, "-o");
  const render::Mode mode =
      render::parse_mode(a.picture.modes.empty() ? "shaded" : a.picture.modes.front(), "--mode");
  if (a.picture.modes.size() > 1)
    throw Error(ErrorCode::kUsage, "give one --mode for one picture", Place{.option = "--mode"});
  const bool needs_data = mode == render::Mode::kDeviation || a.picture.points || a.picture.rows;
  if (needs_data && a.data.empty())
    throw Error(ErrorCode::kUsage,
                std::string(mode == render::Mode::kDeviation ? "the deviation mode"
                            : a.picture.points               ? "--points"
                                                             : "--rows") +
                    " needs the data: give --data INPUT.rows",
                Place{.option = "--data"});
  Point tol_given = Point::Constant(-1);
  if (!a.tol.empty()) tol_given = parse_tolerance(a.tol, "--tol");

  // The surface, and the report sfit writes beside it.
  const nlohmann::json j = io::read_json_file(a.surface);
  const Surface surface = io::surface_from_json(j, a.surface);
  Point report_tol = Point::Constant(-1);
  std::string report_worst;
  if (j.contains("report") && j["report"].is_object()) {
    const auto& r = j["report"];
    try {
      if (r.contains("tolerance") && r["tolerance"].is_array() && r["tolerance"].size() == 3)
        report_tol = Point(r["tolerance"][0].get<double>(), r["tolerance"][1].get<double>(),
                           r["tolerance"][2].get<double>());
      if (r.contains("max_deviation") && r.contains("worst") && report_tol.x() >= 0) {
        const Point m(r["max_deviation"][0].get<double>(), r["max_deviation"][1].get<double>(),
                      r["max_deviation"][2].get<double>());
        report_worst =
            fmt::format("the report (at the fitted parameters): max |d|/T {} at row {} point {}",
                        g(render::tolerance_ratio(m, report_tol, 0)), r["worst"]["row"].get<long>(),
                        r["worst"]["index"].get<long>());
      }
    } catch (const nlohmann::json::exception&) {
      report_tol = Point::Constant(-1);  // a report sfit did not write: ignore it
    }
  }

  Input data;
  const bool have_data = !a.data.empty();
  if (have_data) data = read_input(a.data);
  render::Scene scene;
  scene.surface = &surface;
  std::vector<render::ClosestPoint> closest;
  std::vector<Point> deviations;
  std::vector<double> row_v;
  Point tol = tol_given.x() >= 0 ? tol_given : report_tol;
  std::string tol_note;
  if (have_data) {
    scene.rows = &data.rows;
    if (!(tol.x() >= 0)) {
      tol = relative_tolerance(data.rows, 1e-3);
      tol_note = "T = 1e-3 of the diagonal";
    }
    if (mode == render::Mode::kDeviation || a.picture.rows) {
      const auto t0 = std::chrono::steady_clock::now();
      closest = render::closest_points(surface, data.rows.points());
      say(fmt::format(
          "closest points of {} data points: {:.2f} s", closest.size(),
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()));
      deviations.reserve(closest.size());
      double largest = 0;
      for (const auto& c : closest) {
        deviations.push_back(c.deviation);
        largest = std::max(largest, c.deviation.cwiseAbs().maxCoeff());
      }
      row_v = render::row_parameters(surface, data.rows, closest);
      scene.deviations = deviations;
      scene.row_v = row_v;
      scene.tolerance = tol;
      scene.zero_scale = largest > 0 ? largest : 1;
      scene.deviation_note = "closest points";
    }
  }
  render::RenderOptions o = picture_options(a.picture, mode);
  o.title = {a.picture.title.empty()
                 ? fmt::format("{} \xC2\xB7 {}", base_name(a.surface), render::to_string(mode))
                 : a.picture.title,
             describe(surface, have_data ? data.rows.total_points() : 0,
                      have_data ? data.rows.size() : 0, tol.x() >= 0 ? &tol : nullptr, a.picture)};
  render::RenderResult r;
  try {
    r = render::render_surface(scene, o);
  } catch (const Error& e) {  // the surface's own fault: name its file
    if (e.code() != ErrorCode::kInputData || !e.place().file.empty()) throw;
    throw Error(e.code(), e.message(), Place{.file = a.surface}, e.values());
  }
  if (mode == render::Mode::kDeviation && r.worst_point >= 0) {
    const auto& off = data.rows.offsets();
    const long row =
        static_cast<long>(std::upper_bound(off.begin(), off.end(), r.worst_point) - off.begin()) -
        1;
    const Eigen::Vector3d px = r.camera.project(data.rows.points()[r.worst_point]);
    say(fmt::format(
        "closest-point deviation: max |d|/T {} at row {} point {}, pixel ({:.0f}, {:.0f}){}{}",
        g(r.worst_ratio), row, r.worst_point - static_cast<long>(off[row]), px.x(), px.y(),
        tol_note.empty() ? "" : "; " + tol_note, report_worst.empty() ? "" : "; " + report_worst));
  }
  say(fmt::format("drew {}x{}, {} mode, {:.2f} s", r.image.width, r.image.height,
                  render::to_string(mode), r.seconds));
  plan.write_all([&](const PlannedOutput& out, std::string*) {
    render::write_png(out.path, r.image);
    return std::string();
  });
  return 0;
}

struct RowArgs : FitOptionArgs {  // --degree, --closed, --tol, ... checked as 'fit' does
  std::string input;
  std::string output;
  long row = -1;
  std::string size = "960x720";
  bool quiet = false;
};

int run_render_rows(const RowArgs& a) {
  verbose = !a.quiet;
  if (a.output.empty())
    throw Error(ErrorCode::kUsage, "nothing to write: give -o PICTURE.png", Place{.option = "-o"});
  OutputPlan plan;
  plan.add_input(a.input);
  plan.add(a.output, "-o", OutputTarget::kPicture);
  const auto [w, h] = parse_size(a.size, "--size", 256);
  const CheckedFitOptions checked = check_fit_options(a);
  const bool closed = checked.options.closed_u;

  Input in = read_input(a.input);
  if (a.row < 0 || a.row >= static_cast<long>(in.rows.size()))
    throw Error(ErrorCode::kUsage,
                fmt::format("row {} does not exist: {} has rows 0 ... {}", a.row, in.name,
                            in.rows.size() - 1),
                Place{.option = "--row"}, {static_cast<double>(a.row)});
  const Point tol = checked.tolerance(in.rows);
  const auto row = in.rows[static_cast<std::size_t>(a.row)];
  for (std::size_t k = 0; k < row.size(); ++k)
    if (!row[k].allFinite())
      throw Error(ErrorCode::kInputData, "coordinate is not a finite number",
                  Place{.file = in.name,
                        .line = a.row < static_cast<long>(in.first_line.size())
                                    ? in.first_line[a.row] + static_cast<long>(k)
                                    : -1},
                  {row[k].x(), row[k].y(), row[k].z()});
  if (closed && row.size() == 2)
    throw Error(ErrorCode::kInputData,
                "a closed row needs at least 3 points (or 1 for a pole), got 2",
                Place{.file = in.name, .row = a.row}, {2.0});
  // The curve stage of the surface fit: this row within T/2 per axis.
  const Point bound = 0.5 * tol;
  CurveFitOptions co{checked.options.degree_u, closed, bound, checked.options.search};
  const Parametrization rule = checked.options.parametrization;
  std::vector<double> positions;
  if (rule != Parametrization::kPaper) positions = normalized_positions(row, rule, closed);
  co.positions = positions;
  const CurveFit fit = fit_curve(row, co);
  render::RowPictureOptions o;
  o.width = w;
  o.height = h;
  o.title = {fmt::format("{} \xC2\xB7 row {} of {}: {} points{}", base_name(in.name), a.row,
                         in.rows.size(), row.size(), closed ? ", closed" : ""),
             fmt::format("curve stage: degree {}, {} control points, bound T/2 = {} per axis "
                         "(T = {}); band = curve \xC2\xB1 bound",
                         fit.curve.degree, fit.curve.count(), vec(bound), vec(tol))};
  const render::RowPicture pic = render::render_row(row, fit, bound, o);
  say(fmt::format("row {}: {} points, {} control points (degree {}), max |d|/(T/2) {} at point {}",
                  a.row, row.size(), fit.curve.count(), fit.curve.degree, g(pic.worst_ratio),
                  pic.worst_index));
  plan.write_all([&](const PlannedOutput& out, std::string*) {
    render::write_png(out.path, pic.image);
    return std::string();
  });
  return 0;
}

}  // namespace

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
  const auto [w, h] = parse_size(a.size, "--size", 64);
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
    o.title = {a.title.empty() ? fmt::format("{} \xC2\xB7 {}", base_name(input_name), m) : a.title,
               describe(fit.surface, rows.total_points(), rows.size(), &fit.report.tolerance, a)};
    const render::RenderResult r = render::render_surface(scene, o);
    if (mode == render::Mode::kDeviation && r.worst_point >= 0) {
      const Eigen::Vector3d px = r.camera.project(rows.points()[r.worst_point]);
      say(fmt::format(
          "deviation picture: max |d|/T {} at point {} of the input, pixel ({:.0f}, {:.0f})",
          g(r.worst_ratio), r.worst_point, px.x(), px.y()));
    }
    render::write_png(pngs[i], r.image);  // held back until every output is written
    say(fmt::format("drew {} ({}x{}, {} mode, {:.2f} s)", pngs[i], r.image.width, r.image.height, m,
                    r.seconds));
  }
}

void add_render_commands(CLI::App& app, Runner& run) {
  {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* c = app.add_subcommand("render", "draw a saved surface (.json) to a PNG picture");
    c->add_option("SURFACE", args->surface, "surface file written by 'sfit fit' (.json)")
        ->required();
    c->add_option("-o,--output", args->output, "the picture (.png)");
    c->add_option("--data", args->data,
                  "the data rows (.rows): for --points, --rows and the deviation mode");
    c->add_option("--tol", args->tol,
                  "tolerance T or Tx,Ty,Tz for the deviation colours (default: the report's in the "
                  "surface file, else 1e-3 of the data's diagonal)");
    c->add_flag("-q,--quiet", args->quiet, "print errors only");
    add_picture_options(c, args->picture, "Picture");
    c->footer(
        "Examples:\n"
        "  sfit render hull.json -o hull.png\n"
        "  sfit render hull.json --mode zebra --view side --size 800x600 -o hull-zebra.png\n"
        "  sfit render hull.json --data examples/ship_px121_stations.rows --mode deviation -o "
        "dev.png\n"
        "  sfit render dem.json --mode gauss --view top --exaggerate 5 --net -o dem-K.png\n"
        "Deviations here are to the closest surface point (a lower bound of the report's, which\n"
        "are at the fitted parameters); 'sfit fit --png' draws the report's own.");
    c->callback([args, &run] { run = [args] { return run_render(*args); }; });
  }
  {
    auto args = std::make_shared<RowArgs>();
    CLI::App* c = app.add_subcommand("render-rows",
                                     "draw one row, its fitted curve and the tolerance band (PNG)");
    c->add_option("INPUT", args->input, "rows of points (.rows)")->required();
    c->add_option("--row", args->row, "the row to draw, 0-based")->required();
    c->add_option("-o,--output", args->output, "the picture (.png)");
    c->add_option("--degree", args->degree, "degree of the curve, 1 ... 20 (default 3)");
    c->add_option("--closed", args->choices["closed"], "u: the row is a closed contour");
    c->add_option("--tol", args->tol,
                  "tolerance T or Tx,Ty,Tz of the surface fit (the row gets T/2)");
    c->add_option("--tol-rel", args->tol_rel,
                  "tolerance as a fraction of the data's bounding-box diagonal");
    c->add_option("--search", args->choices["search"], "count search: fast (default) or linear")
        ->check(CLI::IsMember({"fast", "linear"}));
    c->add_option("--parameters", args->choices["parameters"],
                  "paper (default), uniform, chord or centripetal, as sfit fit --parameters")
        ->check(CLI::IsMember({"paper", "uniform", "chord", "centripetal"}));
    c->add_option("--size", args->size, "picture size WIDTHxHEIGHT (default 960x720)");
    c->add_flag("-q,--quiet", args->quiet, "print errors only");
    c->footer(
        "Example:\n"
        "  sfit render-rows examples/iea3p4mw_blade_ragged9.rows --row 4 --closed u -o row4.png\n"
        "The row is fitted as the curve stage of 'sfit fit' does: within T/2 per axis.");
    c->callback([args, &run] { run = [args] { return run_render_rows(*args); }; });
  }
}

}  // namespace sfit::cli
