// sfit fit: the main job.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <optional>

#include "cli_common.h"
#include "commands.h"
#include "output_plan.h"
#include "outputs.h"
#include "progress_line.h"
#include "sfit/error.h"
#include "sfit/fit_limits.h"
#include "sfit/fold_check.h"
#include "sfit/io/atomic_file.h"
#include "sfit/io/formats.h"
#include "sfit/io/surface_json.h"
#include "sfit/option_names.h"
#include "sfit/surface_fit.h"
#include "surface_json_value.h"
#ifdef SFIT_HAVE_RENDER
#include "picture_options.h"
#endif

namespace sfit::cli {
namespace {

struct FitArgs : FitOptionArgs {  // --degree, --tol, --closed, ... (cli_common.h)
  std::string input;
  std::vector<std::string> outputs;
  std::string report;
  bool quiet = false;
  OutputShapeArgs shape;  // --mesh ... --units; units "": a STEP/IGES input's unit, else mm
#ifdef SFIT_HAVE_RENDER
  std::vector<std::string> pngs;  // --png pictures
  PictureArgs picture;
#endif
};

// Maps a data error of the fit onto the input file (and file:line for a row-level one).
[[noreturn]] void rethrow_with_file(const Error& e, const Input& in) {
  Place p = e.place();
  if (p.file.empty() && p.option.empty()) {
    p.file = in.name;
    if (p.row >= 0 && p.row < static_cast<long>(in.first_line.size()))
      p.line = in.first_line[p.row] + std::max(0L, p.point);
  }
  throw Error(e.code(), e.message(), p, e.values());
}

std::string g(double x) {
  return fmt::format("{:.4g}", x);
}
std::string vec(const Point& p) {
  if (p.x() == p.y() && p.y() == p.z()) return g(p.x());
  return fmt::format("({}, {}, {})", g(p.x()), g(p.y()), g(p.z()));
}

int run_fit(const FitArgs& a) {
  verbose = !a.quiet;
  const CheckedFitOptions checked = check_fit_options(a);
  FitOptions o = checked.options;
  // Every output planned and checked before reading or fitting anything.
  OutputPlan plan;
  plan.add_input(a.input);
  plan.add(a.outputs, "-o", OutputTarget::kSurface);
  if (!a.report.empty()) plan.add(a.report, "--report", OutputTarget::kReport);
  check_output_options(a.shape.units.empty() ? "mm" : a.shape.units, a.shape.mesh_density,
                       a.shape.normals);
#ifdef SFIT_HAVE_RENDER
  plan.add(a.pngs, "--png", OutputTarget::kPicture);
  check_picture_outputs(a.pngs, a.picture, "--png");
#endif

  Input in = read_input(a.input);
  const BoundingBox box = bounding_box(in.rows);
  o.tolerance = checked.tolerance(in.rows);
  note_closed_rows(in, o.closed_u, !a.closed().empty());
  const std::string units = units_of_outputs(a.shape.units, in);

  std::size_t lo = SIZE_MAX, hi = 0;
  for (std::size_t j = 0; j < in.rows.size(); ++j) {
    lo = std::min(lo, in.rows[j].size());
    hi = std::max(hi, in.rows[j].size());
  }
  say(fmt::format("{}: {} rows, {} points ({}..{} per row){}{}", in.name, in.rows.size(),
                  in.rows.total_points(), lo, hi, o.closed_u ? ", closed rows" : "",
                  o.closed_v ? ", closed row sequence" : ""));
  say(fmt::format("degree {} x {}, tolerance {}{}", o.degree_u, o.degree_v, vec(o.tolerance),
                  !checked.relative() ? ""
                                      : fmt::format(" ({} of the diagonal {})", g(checked.fraction),
                                                    g(box.diagonal()))));
  // SIGINT/SIGTERM stop the fit at its next check and the run writes nothing (exit 128 +
  // the signal); a line on a terminal shows the progress of a fit taking over a second.
  const Interruption interrupt;
  auto interrupted = [&] {
    std::fprintf(stderr, "sfit: error: %s: %s; nothing written\n", in.name.c_str(),
                 interrupt.what().c_str());
    return interrupt.exit_code();
  };
  ProgressLine line(verbose);
  o.progress = line.function(interrupt);
  o.cancel = interrupt.flag();

  FitResult fit;
  try {
    fit = fit_surface(in.rows, o);
  } catch (const Error& e) {
    line.clear();
    if (e.code() == ErrorCode::kCancelled && interrupt.signal() != 0) return interrupted();
    rethrow_with_file(e, in);
  }
  line.clear();
  if (interrupt.signal() != 0) return interrupted();
  const FitReport& r = fit.report;
  const auto [rmin, rmax] = std::minmax_element(r.row_counts.begin(), r.row_counts.end());
  const auto [cmin, cmax] = std::minmax_element(r.column_counts.begin(), r.column_counts.end());
  // The two stages' counts (empty where the surface search did not need to run them).
  const std::string stages =
      r.row_counts.empty() || r.column_counts.empty()
          ? ""
          : fmt::format(" (rows need {}..{}, columns {}..{})", *rmin, *rmax, *cmin, *cmax);
  say(fmt::format("surface {} x {} control points{}; {} parameters", r.count_u, r.count_v, stages,
                  to_string(r.parametrization)));
  if (r.knots == KnotRule::kCorners)
    say(
        fmt::format("corner knots: {} x {} control points, a crease at each corner matched "
                    "across the rows, chord parameters remapped to the corners",
                    r.count_u, r.count_v));
  if (o.knots == KnotRule::kAdaptive)
    say(r.knots == KnotRule::kAdaptive
            ? fmt::format("adaptive knots: {} x {} control points, fewer than on uniform knots",
                          r.count_u, r.count_v)
            : std::string("adaptive knots: none smaller than uniform held; uniform knots kept"));
  if (r.degree_v != o.degree_v)
    say(
        fmt::format("degree across the rows {} (asked: {}): at {} the surface folded back on "
                    "itself under every rule across them (--no-fold-guard keeps it)",
                    r.degree_v, o.degree_v, o.degree_v));
  if (r.method == FitMethod::kSurface || o.method == FitMethod::kSurface)
    say(fmt::format("method {} ({} norm, {} pairs tried): {}", to_string(r.method),
                    to_string(r.norm), r.pairs_tried, r.stop_reason));
  if (r.knots == KnotRule::kCorners) {
    // the corner line above says which parameters
  } else if (o.method == FitMethod::kSurface && !r.rules_searched.empty() &&
             (o.parametrization == Parametrization::kFewest ||
              o.parametrization == Parametrization::kAuto)) {
    std::string searched;
    for (Parametrization p : r.rules_searched)
      searched += (searched.empty() ? "" : ", ") + std::string(to_string(p));
    if (r.method == FitMethod::kSurface)
      say(fmt::format("{} parameters gave the fewest control points of the rules searched ({})",
                      to_string(r.parametrization), searched));
    else
      say(
          fmt::format("{} parameters: the two stages' fit, kept over the search's surfaces "
                      "under {} (the reason above)",
                      to_string(r.parametrization), searched));
  } else if (o.method == FitMethod::kSfit01 && o.parametrization == Parametrization::kFewest)
    say(fmt::format("{} parameters gave the fewest control points of the four rules",
                    to_string(r.parametrization)));
  else if (o.parametrization != Parametrization::kAuto && r.parametrization != o.parametrization)
    say(fmt::format("note: {} parameters could not hold the tolerance here; the paper's did",
                    to_string(o.parametrization)));
  double used = 0;
  for (int k = 0; k < 3; ++k)
    if (r.tolerance[k] > 0) used = std::max(used, r.max_deviation[k] / r.tolerance[k]);
  say(fmt::format("max deviation {} ({}% of T); worst: row {} point {}, deviation {}",
                  vec(r.max_deviation), g(100 * used), r.worst_row, r.worst_index,
                  vec(r.worst_deviation)));
  say(fmt::format("every point within tolerance: {}; {:.3f} s", r.within_tolerance ? "yes" : "NO",
                  r.seconds));
  if ((r.tolerance.array() == 0).any())  // the allowance applies at T = 0 only (docs/errors.md)
    say(fmt::format("T = 0 allows round-off: deviations up to {} ({} of the diagonal)",
                    g(r.roundoff), g(kRoundoffRelative)));
  {  // Seams and shape measures (docs/seams.md).
    int moved = 0, reversed = 0;
    for (const RowSeam& s : r.seams) {
      moved += s.shift != 0 || s.offset != 0;
      reversed += s.reversed;
    }
    if (moved || reversed)
      say(
          fmt::format("seams: {} rows start elsewhere, {} rows reversed (--seam/--orient keep: as "
                      "given)",
                      moved, reversed));
    if (r.parametrization_across != r.parametrization && r.method == FitMethod::kSfit01)
      say(fmt::format("{} parameters across the rows: the surface folded with {}",
                      to_string(r.parametrization_across), to_string(r.parametrization)));
    say(fmt::format("shape: fold {}, out of the data's box by {}, farthest from the rows {}",
                    g(r.fold), g(r.box_excursion), g(r.row_gap)));
    if (r.fold > kFoldRelative * box.diagonal())
      say(fmt::format(
          "warning: the surface folds back on itself by {} between rows ({}); "
          "meshes and offsets of it will fail",
          g(r.fold),
          o.fold_guard ? (o.degree_v > 1 ? "no rule across the rows avoided it; a lower degree "
                                           "across them (--degree-v) may"
                                         : "no rule across the rows avoided it")
                       : "--no-fold-guard"));
  }
  if (!r.within_tolerance)
    throw Error(
        ErrorCode::kToleranceNotMet,
        fmt::format("the surface misses the tolerance at row {} point {} by {}; nothing written",
                    r.worst_row, r.worst_index, vec(r.worst_deviation)),
        Place{.file = in.name},
        {r.worst_deviation.x(), r.worst_deviation.y(), r.worst_deviation.z()});
  const OutputContext ctx = output_context(a.shape, fit.surface, &fit, &in.rows, in.name, units);
  bool pictures_done = false;
  try {
    plan.write_all([&](const PlannedOutput& out, std::string* text) {
      // A signal before the last output is written: every temporary removed, nothing renamed.
      if (interrupt.signal() != 0) throw Error(ErrorCode::kCancelled, interrupt.what());
      switch (out.target) {
        case OutputTarget::kSurface:
          return write_output(out.path, ctx, text);
        case OutputTarget::kReport:
          if (text)
            *text = io::report_to_json(r).dump(2) + "\n";
          else
            io::write_report_json(out.path, r);
          return std::string();
        case OutputTarget::kPicture:
#ifdef SFIT_HAVE_RENDER
          if (!pictures_done) write_fit_pictures(a.pngs, a.picture, fit, in.rows, in.name);
#endif
          pictures_done = true;
          return std::string();
        case OutputTarget::kRows:
          return std::string();
      }
      return std::string();
    });
  } catch (const Error& e) {
    if (e.code() == ErrorCode::kCancelled && interrupt.signal() != 0) return interrupted();
    throw;
  }
  return 0;
}

}  // namespace

void add_fit_command(CLI::App& app, Runner& run) {
  auto args = std::make_shared<FitArgs>();
  CLI::App* c = app.add_subcommand("fit", "fit a surface to rows of points");
  c->add_option("INPUT", args->input,
                "rows of points (" + io::extension_list(io::FormatKind::kRows, true) +
                    "; '-': .rows on standard input)" +
                    (io::find_format("step")->available
                         ? ", or section curves in a .step/.iges file (each curve one row)"
                         : ""))
      ->required();
  c->add_option("-o,--output", args->outputs,
                "output file; the extension picks the format (" +
                    io::extension_list(io::FormatKind::kSurface, false) +
                    "); '-': the JSON on standard output; repeat -o for several; none: "
                    "the summary only");
  c->add_option("--report", args->report, "write the fit report as JSON ('-': standard output)");
  add_fit_option_flags(c, *args);
  // Mesh and CAD outputs (.obj .stl .ply .vtk .vts .step .igs); the default units "" is the
  // input's own unit, else mm (units_of_outputs()).
  add_output_shape_options(c, args->shape);
#ifdef SFIT_HAVE_RENDER
  CLI::Option* png = c->add_option("--png", args->pngs,
                                   "draw the fitted surface to a PNG picture (repeat for several; "
                                   "see the Picture options)");
  png->group("Picture");
  add_picture_options(c, args->picture, "Picture", png);
#endif
  c->add_flag("-q,--quiet", args->quiet, "print errors only");
  c->footer(
      "Examples:\n"
      "  sfit fit examples/ship_px121_stations.rows -o hull.json\n"
      "  sfit fit blade.rows --closed u --tol 0.001 -o blade.json --report blade-report.json\n"
      "  sfit fit terrain.rows --degree-u 3 --degree-v 2 --tol 1,1,0.1 -o dem.json\n"
      "  cat scan.rows | sfit fit - --tol-rel 1e-4 -o scan.json\n"
      "  sfit fit scan_lines.rows --parameters chord -o scan.json   # unevenly sampled rows\n"
      "The summary goes to stderr; exit code 7 means the tolerance could not be held\n"
      "(nothing is written then).");
  c->callback([args, &run] { run = [args] { return run_fit(*args); }; });
}

}  // namespace sfit::cli
