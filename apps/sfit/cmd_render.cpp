// sfit render and sfit render-rows (the picture options: picture_options.cpp).
#include <fmt/format.h>

#include <algorithm>
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
                        format_number(render::tolerance_ratio(m, report_tol, 0)),
                        r["worst"]["row"].get<long>(), r["worst"]["index"].get<long>());
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
  o.title = {
      a.picture.title.empty()
          ? fmt::format("{} \xC2\xB7 {}", display_name(a.surface), render::to_string(mode))
          : a.picture.title,
      describe_surface(surface, have_data ? data.rows.total_points() : 0,
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
        format_number(r.worst_ratio), row, r.worst_point - static_cast<long>(off[row]), px.x(),
        px.y(), tol_note.empty() ? "" : "; " + tol_note,
        report_worst.empty() ? "" : "; " + report_worst));
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
  const auto [w, h] = parse_picture_size(a.size, "--size", 256);
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
  o.title = {
      fmt::format("{} \xC2\xB7 row {} of {}: {} points{}", display_name(in.name), a.row,
                  in.rows.size(), row.size(), closed ? ", closed" : ""),
      fmt::format("curve stage: degree {}, {} control points, bound T/2 = {} per axis "
                  "(T = {}); band = curve \xC2\xB1 bound",
                  fit.curve.degree, fit.curve.count(), format_point(bound), format_point(tol))};
  const render::RowPicture pic = render::render_row(row, fit, bound, o);
  say(fmt::format("row {}: {} points, {} control points (degree {}), max |d|/(T/2) {} at point {}",
                  a.row, row.size(), fit.curve.count(), fit.curve.degree,
                  format_number(pic.worst_ratio), pic.worst_index));
  plan.write_all([&](const PlannedOutput& out, std::string*) {
    render::write_png(out.path, pic.image);
    return std::string();
  });
  return 0;
}

}  // namespace

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
