// sfit fit: the main job.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <optional>

#include "cli_common.h"
#include "commands.h"
#include "outputs.h"
#include "sfit/error.h"
#include "sfit/fold_check.h"
#include "sfit/io/atomic_file.h"
#include "sfit/io/surface_json.h"
#include "sfit/surface_fit.h"
#ifdef SFIT_HAVE_RENDER
#include "picture_options.h"
#endif

namespace sfit::cli {
namespace {

struct FitArgs {
  std::string input;
  std::vector<std::string> outputs;
  std::string report;
  int degree = 3;
  std::optional<int> degree_u, degree_v;  // unset: --degree
  std::optional<std::string> tol;
  std::optional<double> tol_rel;
  std::string closed;
  std::string search = "fast";
  std::string parameters = "paper";
  std::string seam = "align", orient = "auto", rerepresent = "paper";  // docs/seams.md
  int threads = 0;
  bool quiet = false;
  bool no_fold_guard = false;  // docs/seams.md
  bool mesh = false;
  int mesh_density = 0;
  bool fields = false;
  std::string units = "mm";
#ifdef SFIT_HAVE_RENDER
  std::vector<std::string> pngs;  // --png pictures
  PictureArgs picture;
#endif
};

#ifdef SFIT_HAVE_RENDER
bool wants_pictures(const FitArgs& a) {
  return !a.pngs.empty();
}
#else
bool wants_pictures(const FitArgs&) {
  return false;
}
#endif

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
  FitOptions o;
  o.degree_u = a.degree_u.value_or(a.degree);
  o.degree_v = a.degree_v.value_or(a.degree);
  auto check_degree = [](int d, const char* opt) {
    if (d < 1 || d > 20)
      throw Error(ErrorCode::kUsage, fmt::format("degree {} is out of range 1 ... 20", d),
                  Place{.option = opt}, {static_cast<double>(d)});
  };
  check_degree(a.degree, "--degree");
  if (a.degree_u) check_degree(*a.degree_u, "--degree-u");
  if (a.degree_v) check_degree(*a.degree_v, "--degree-v");
  if (a.closed == "u" || a.closed == "uv" || a.closed == "vu") o.closed_u = true;
  if (a.closed == "v" || a.closed == "uv" || a.closed == "vu") o.closed_v = true;
  if (!a.closed.empty() && a.closed != "none" && !o.closed_u && !o.closed_v)
    throw Error(ErrorCode::kUsage, "'" + a.closed + "' is not one of u, v, uv, none",
                Place{.option = "--closed"});
  o.search = a.search == "linear" ? CountSearch::kLinear : CountSearch::kFast;
  parse_parametrization(a.parameters, o.parametrization);  // checked by CLI11
  o.threads = a.threads;
  o.fold_guard = !a.no_fold_guard;
  if (!parse_seam_mode(a.seam, o.seam))
    throw Error(ErrorCode::kUsage, "'" + a.seam + "' is not one of align, keep",
                Place{.option = "--seam"});
  if (!parse_resampling(a.rerepresent, o.rerepresentation))
    throw Error(ErrorCode::kUsage, "'" + a.rerepresent + "' is not one of paper, arc_length",
                Place{.option = "--rerepresent"});
  if (!parse_orient_mode(a.orient, o.orient))
    throw Error(ErrorCode::kUsage, "'" + a.orient + "' is not one of auto, keep",
                Place{.option = "--orient"});
  if (a.tol && a.tol_rel)
    throw Error(ErrorCode::kUsage, "give --tol or --tol-rel, not both",
                Place{.option = "--tol-rel"});
  if (a.tol_rel && !(*a.tol_rel >= 0 && *a.tol_rel <= 1))
    throw Error(
        ErrorCode::kUsage,
        fmt::format("must be a fraction 0 ... 1 of the bounding-box diagonal, got {}", *a.tol_rel),
        Place{.option = "--tol-rel"}, {*a.tol_rel});
  Point tol_abs = Point::Constant(-1);
  if (a.tol) tol_abs = parse_tolerance(*a.tol, "--tol");
  if (a.outputs.empty() && a.report.empty() && !wants_pictures(a))
    throw Error(ErrorCode::kUsage, "nothing to write: give -o OUT.json (and/or --report)",
                Place{.option = "-o"});
  // Refuse impossible outputs before reading or fitting anything.
  for (const auto& out : a.outputs) {
    check_output_extension(out);
    io::check_writable(out);
  }
  if (!a.report.empty()) io::check_writable(a.report);
  check_units(a.units);
#ifdef SFIT_HAVE_RENDER
  check_picture_outputs(a.pngs, a.picture, "--png");
#endif

  Input in = read_input(a.input);
  const BoundingBox box = bounding_box(in.rows);
  const double fraction = a.tol_rel.value_or(1e-3);
  o.tolerance = tol_abs.x() >= 0 ? tol_abs : Point::Constant(fraction * box.diagonal());

  std::size_t lo = SIZE_MAX, hi = 0;
  for (std::size_t j = 0; j < in.rows.size(); ++j) {
    lo = std::min(lo, in.rows[j].size());
    hi = std::max(hi, in.rows[j].size());
  }
  say(fmt::format("{}: {} rows, {} points ({}..{} per row){}{}", in.name, in.rows.size(),
                  in.rows.total_points(), lo, hi, o.closed_u ? ", closed rows" : "",
                  o.closed_v ? ", closed row sequence" : ""));
  say(fmt::format("degree {} x {}, tolerance {}{}", o.degree_u, o.degree_v, vec(o.tolerance),
                  tol_abs.x() >= 0
                      ? ""
                      : fmt::format(" ({} of the diagonal {})", g(fraction), g(box.diagonal()))));
  const bool show_progress = verbose && in.rows.total_points() >= 200000 && isatty(2);
  if (show_progress)
    o.progress = [](std::string_view stage, std::size_t done, std::size_t total) {
      std::fprintf(stderr, "sfit: fitting %.*s %zu/%zu\r", static_cast<int>(stage.size()),
                   stage.data(), done, total);
      if (done == total) std::fprintf(stderr, "\n");
    };

  FitResult fit;
  try {
    fit = fit_surface(in.rows, o);
  } catch (const Error& e) {
    rethrow_with_file(e, in);
  }
  const FitReport& r = fit.report;
  const auto [rmin, rmax] = std::minmax_element(r.row_counts.begin(), r.row_counts.end());
  const auto [cmin, cmax] = std::minmax_element(r.column_counts.begin(), r.column_counts.end());
  say(fmt::format(
      "surface {} x {} control points (rows need {}..{}, columns {}..{}); {} parameters", r.count_u,
      r.count_v, *rmin, *rmax, *cmin, *cmax, to_string(r.parametrization)));
  if (o.parametrization == Parametrization::kFewest)
    say(fmt::format("{} parameters gave the fewest control points of the four rules",
                    to_string(r.parametrization)));
  else if (r.parametrization != o.parametrization)
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
  {  // Seams and shape measures (docs/seams.md).
    int moved = 0, reversed = 0;
    for (const RowSeam& s : r.seams) {
      moved += s.shift != 0 || s.offset != 0;
      reversed += s.reversed;
    }
    if (moved || reversed)
      say(fmt::format("seams: {} rows start elsewhere, {} rows reversed (--seam/--orient keep: as "
                      "given)",
                      moved, reversed));
    if (r.parametrization_across != r.parametrization)
      say(fmt::format("{} parameters across the rows: the surface folded with {}",
                      to_string(r.parametrization_across), to_string(r.parametrization)));
    say(fmt::format("shape: fold {}, out of the data's box by {}, farthest from the rows {}",
                    g(r.fold), g(r.box_excursion), g(r.row_gap)));
    if (r.fold > kFoldRelative * box.diagonal())
      say(fmt::format("warning: the surface folds back on itself by {} between rows ({}); "
                      "meshes and offsets of it will fail",
                      g(r.fold),
                      o.fold_guard ? "no rule across the rows avoided it" : "--no-fold-guard"));
  }
  if (!r.within_tolerance)
    throw Error(
        ErrorCode::kToleranceNotMet,
        fmt::format("the surface misses the tolerance at row {} point {} by {}; nothing written",
                    r.worst_row, r.worst_index, vec(r.worst_deviation)),
        Place{.file = in.name},
        {r.worst_deviation.x(), r.worst_deviation.y(), r.worst_deviation.z()});
  OutputContext ctx{fit.surface, &fit,           &in.rows, in.name,
                    a.mesh,      a.mesh_density, a.fields, a.units};
  for (const auto& out : a.outputs) {
    write_output(out, ctx);
    say("wrote " + out);
  }
  if (!a.report.empty()) {
    io::write_report_json(a.report, r);
    say("wrote " + a.report);
  }
#ifdef SFIT_HAVE_RENDER
  write_fit_pictures(a.pngs, a.picture, fit, in.rows, in.name);
#endif
  return 0;
}

}  // namespace

void add_fit_command(CLI::App& app, Runner& run) {
  auto args = std::make_shared<FitArgs>();
  CLI::App* c = app.add_subcommand("fit", "fit a surface to rows of points");
  c->add_option("INPUT", args->input,
                "rows of points: .rows or .csv file ('-': .rows on standard input), or "
                "section curves in a .step/.iges file (each curve one row)")
      ->required();
  c->add_option("-o,--output", args->outputs,
                "output file; the extension picks the format (.json .step .igs .obj .stl .ply "
                ".vtk .vts; repeat -o for several)");
  c->add_option("--report", args->report, "write the fit report as JSON");
  c->add_option("--degree", args->degree, "degree in both directions, 1 ... 20")->default_val(3);
  c->add_option("--degree-u", args->degree_u, "degree along the rows (overrides --degree)");
  c->add_option("--degree-v", args->degree_v, "degree across the rows (overrides --degree)");
  c->add_option("--tol", args->tol,
                "tolerance T or Tx,Ty,Tz, absolute, >= 0 (0 interpolates); "
                "default 1e-3 of the bounding-box diagonal");
  c->add_option("--tol-rel", args->tol_rel, "tolerance as a fraction of the bounding-box diagonal");
  c->add_option("--closed", args->closed,
                "closed directions: u (each row is a closed contour), v (the rows form a "
                "closed sequence), uv (both), none");
  c->add_option("--search", args->search, "count search: fast (default) or linear (the paper's)")
      ->check(CLI::IsMember({"fast", "linear"}));
  c->add_option("--parameters", args->parameters,
                "how points get parameters, along and across the rows: paper (SFIT01's, by the "
                "point's index; default), uniform (index), chord (chord length), centripetal, or "
                "fewest (tries the four, keeps the fewest control points)")
      ->check(CLI::IsMember({"paper", "uniform", "chord", "centripetal", "fewest"}));
  c->add_option("--seam", args->seam,
                "closed rows: align (default: each row starts where its neighbour starts, "
                "same direction) or keep (as given: the paper's scheme)");
  c->add_option("--orient", args->orient,
                "auto (default: a row running against its neighbour is reversed) or keep");
  c->add_flag("--no-fold-guard", args->no_fold_guard,
              "keep a surface that folds between rows (with --seam keep --orient keep: the "
              "paper's scheme exactly)");
  c->add_option("--rerepresent", args->rerepresent,
                "where the re-representation samples each row curve: paper (default) or "
                "arc_length (equal arc length, open rows)");
  c->add_option("--threads", args->threads, "threads (0: all cores); results do not depend on it")
      ->check(CLI::Range(0, 4096));
  c->add_flag("--mesh", args->mesh, "write .obj as a tessellated mesh (not free-form)");
  c->add_option("--mesh-density", args->mesh_density,
                "tessellation samples per direction (default: from the tolerance)");
  c->add_flag("--fields", args->fields, "add deviation and curvature point data (.vtk/.vts)");
  c->add_option("--units", args->units,
                "length unit the STEP/IGES file states (mm, cm, m, km, um, in, ft, mi); "
                "coordinates are written unchanged")
      ->default_val("mm");
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
