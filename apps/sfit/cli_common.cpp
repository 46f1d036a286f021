#include "cli_common.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "sfit/error.h"
#include "sfit/fit_limits.h"
#include "sfit/io/csv_reader.h"
#include "sfit/io/file_names.h"
#include "sfit/io/formats.h"
#include "sfit/io/rows_binary.h"
#include "sfit/io/rows_reader.h"
#include "sfit/option_names.h"
#ifdef SFIT_HAVE_EXCHANGE
#include "sfit/exchange/readers.h"
#endif

namespace sfit::cli {

bool verbose = true;

void say(const std::string& line) {
  if (verbose) std::fprintf(stderr, "sfit: %s\n", line.c_str());
}

namespace {

// CLI11 reads "010" as octal and "0x10" as hex: give it plain decimal digits only.
std::string decimal_integer(std::string& text) {
  std::size_t i = 0;
  std::string sign;
  if (!text.empty() && (text[0] == '-' || text[0] == '+')) {
    if (text[0] == '-') sign = "-";
    i = 1;
  }
  if (text.empty()) return "empty value";
  if (i == text.size()) return "'" + text + "' is not a whole number";
  for (std::size_t k = i; k < text.size(); ++k)
    if (!std::isdigit(static_cast<unsigned char>(text[k])))
      return "'" + text + "' is not a whole decimal number";
  while (i + 1 < text.size() && text[i] == '0') ++i;
  text = sign + text.substr(i);
  return "";
}

void harden(CLI::App& app) {
  for (CLI::Option* o : app.get_options()) {
    if (o->get_type_size_max() == 0) continue;  // a flag
    o->check(CLI::Validator(
        [](std::string& v) { return v.empty() ? std::string("empty value") : std::string(); }, "",
        "non-empty"));
    const std::string t = o->get_type_name();
    if (t == "INT" || t == "UINT") o->transform(CLI::Validator(decimal_integer, "", "decimal"));
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) harden(*sub);
}

}  // namespace

void harden_options(CLI::App& app) {
  harden(app);
}

Point CheckedFitOptions::tolerance(const Rows& rows) const {
  return relative() ? relative_tolerance(rows, fraction) : absolute;
}

void add_fit_option_flags(CLI::App* c, FitOptionArgs& a) {
  c->add_option("--degree", a.degree,
                fmt::format("degree in both directions, {} ... {}", kMinFitDegree, kMaxFitDegree))
      ->default_val(3);
  c->add_option("--degree-u", a.degree_u, "degree along the rows (overrides --degree)");
  c->add_option("--degree-v", a.degree_v, "degree across the rows (overrides --degree)");
  c->add_option("--tol", a.tol,
                "tolerance T or Tx,Ty,Tz, absolute, >= 0 (0 interpolates); "
                "default 1e-3 of the bounding-box diagonal");
  c->add_option("--tol-rel", a.tol_rel, "tolerance as a fraction of the bounding-box diagonal");
  c->add_option("--closed", a.closed,
                "closed directions: u (each row is a closed contour), v (the rows form a "
                "closed sequence), uv (both), none");
  c->add_option("--search", a.search, "count search: fast (default) or linear (the paper's)")
      ->check(CLI::IsMember({"fast", "linear"}));
  c->add_option("--parameters", a.parameters,
                "how points get parameters, along and across the rows: paper (SFIT01's, by the "
                "point's index), uniform (index), chord (chord length), centripetal, fewest "
                "(tries the four, keeps the fewest control points), or auto (default: the "
                "four with --method surface, paper with --method sfit01)")
      ->check(CLI::IsMember({"paper", "uniform", "chord", "centripetal", "fewest", "auto"}));
  c->add_option("--method", a.method,
                "surface (default: the fewest nu x nv whose surface holds T, searched over all "
                "points at once; never more than sfit01) or sfit01 (the paper's two stages)");
  c->add_option("--norm", a.norm,
                "with --method surface: l2 (least squares), linf (minimax), auto (default: "
                "least squares, minimax where it misses T by a little)");
  c->add_option("--seam", a.seam,
                "closed rows: align (default: each row starts where its neighbour starts, "
                "same direction) or keep (as given: the paper's scheme)");
  c->add_option("--orient", a.orient,
                "auto (default: a row running against its neighbour is reversed) or keep");
  c->add_flag("--no-fold-guard", a.no_fold_guard,
              "keep a surface that folds between rows, at the degree asked for (the guard "
              "tries other rules across the rows, then one degree lower across them; with "
              "--seam keep --orient keep: the paper's scheme exactly)");
  c->add_option("--rerepresent", a.rerepresent,
                "where --method sfit01's re-representation samples each row curve: paper "
                "(default) or arc_length (equal arc length, open rows)");
  c->add_option("--threads", a.threads,
                "threads, 0 (all cores) ... " + std::to_string(kMaxThreads) +
                    "; results do not depend on it");
}

CheckedFitOptions check_fit_options(const FitOptionArgs& a) {
  CheckedFitOptions c;
  FitOptions& o = c.options;
  check_degree(a.degree, "--degree");
  if (a.degree_u) check_degree(*a.degree_u, "--degree-u");
  if (a.degree_v) check_degree(*a.degree_v, "--degree-v");
  o.degree_u = a.degree_u.value_or(a.degree);
  o.degree_v = a.degree_v.value_or(a.degree);
  if (!parse_closed(a.closed, o.closed_u, o.closed_v))
    throw Error(ErrorCode::kUsage, "'" + a.closed + "' is not one of u, v, uv, none",
                Place{.option = "--closed"});
  // The library's names; "known" (counts given as the answer) is for callers with hints.
  if (a.search == "known" || !parse_count_search(a.search, o.search))
    throw Error(ErrorCode::kUsage, "'" + a.search + "' is not one of fast, linear",
                Place{.option = "--search"});
  if (!parse_parametrization(a.parameters, o.parametrization))
    throw Error(ErrorCode::kUsage,
                "'" + a.parameters + "' is not one of paper, uniform, chord, centripetal, fewest",
                Place{.option = "--parameters"});
  if (!parse_fit_method(a.method, o.method))
    throw Error(ErrorCode::kUsage, "'" + a.method + "' is not a method (surface, sfit01)",
                Place{.option = "--method"});
  if (!parse_fit_norm(a.norm, o.norm))
    throw Error(ErrorCode::kUsage, "'" + a.norm + "' is not a norm (l2, linf, auto)",
                Place{.option = "--norm"});
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
  check_threads(a.threads, "--threads");
  o.threads = a.threads;
  if (a.tol && a.tol_rel)
    throw Error(ErrorCode::kUsage, "give --tol or --tol-rel, not both",
                Place{.option = "--tol-rel"});
  if (a.tol_rel) check_tolerance_fraction(*a.tol_rel, "--tol-rel");
  c.fraction = a.tol_rel.value_or(kDefaultToleranceFraction);
  if (a.tol) c.absolute = parse_tolerance(*a.tol, "--tol");
  return c;
}

Point parse_tolerance(const std::string& text, const std::string& option) {
  std::vector<double> v;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string tok =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    double x = 0;
    const char* b = tok.data();
    const char* e = b + tok.size();
    if (b != e && *b == '+') ++b;
    const auto r = std::from_chars(b, e, x);
    if (!tok.empty() && r.ec == std::errc::result_out_of_range && r.ptr == e)
      throw Error(ErrorCode::kUsage, "'" + tok + "' is out of the range of a double",
                  Place{.option = option});
    if (tok.empty() || r.ec != std::errc() || r.ptr != e)
      throw Error(ErrorCode::kUsage, "'" + tok + "' is not a number (expected T or Tx,Ty,Tz)",
                  Place{.option = option});
    if (!std::isfinite(x) || x < 0)
      throw Error(ErrorCode::kUsage, "tolerance must be a finite number >= 0, got '" + tok + "'",
                  Place{.option = option}, {x});
    v.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (v.size() == 1) return Point::Constant(v[0]);
  if (v.size() == 3) return Point(v[0], v[1], v[2]);
  throw Error(ErrorCode::kUsage,
              "expected one tolerance or three (Tx,Ty,Tz), got " + std::to_string(v.size()),
              Place{.option = option});
}

Input read_input(const std::string& path) {
  // Dispatch through the one format registry (sfit/io/formats.h); '-' and unknown
  // extensions are .rows text.
  const std::string ext = path == "-" ? "rows" : io::extension_of(path);
  const io::Format* f = io::find_format(ext);
  const bool rows_format =
      f && f->reads && (f->kind == io::FormatKind::kRows || f->part == io::FormatPart::kCad);
  if (rows_format && !f->available)
    throw Error(ErrorCode::kUsage,
                std::string(f->name) + " input needs " + std::string(io::part_name(f->part)) +
                    ", which this build of sfit lacks",
                Place{.file = path});
  const io::FormatId id = rows_format ? f->id : io::FormatId::kRows;
  if (id == io::FormatId::kCsv) {
    auto r = io::read_csv(path);
    return Input{std::move(r.rows), std::move(r.first_line), std::move(r.name)};
  }
#ifdef SFIT_HAVE_EXCHANGE
  if (id == io::FormatId::kStep || id == io::FormatId::kIges) {
    auto r = exchange::read_sections(path);
    say(path + ": lengths in " + r.units +
        (r.units.find(' ') == std::string::npos ? " (the file's own unit, not converted)" : ""));
    return Input{std::move(r.rows), std::move(r.first_line), path, std::move(r.closed),
                 std::move(r.units)};
  }
#endif
  if (id == io::FormatId::kBinaryRows) {
    auto r = io::read_rows_binary(path);
    return Input{std::move(r.rows), std::move(r.first_line), std::move(r.name)};
  }
  auto r = io::read_rows(path);
  return Input{std::move(r.rows), std::move(r.first_line), std::move(r.name)};
}

namespace {
// The ends of a row meet: the gap from the last point to the first is no longer than twice
// the row's longest step and short against the row's length (a closed contour, whether the
// first point is repeated or not).
bool ends_meet(std::span<const Point> row) {
  if (row.size() < 4) return false;
  double longest = 0, length = 0;
  for (std::size_t k = 1; k < row.size(); ++k) {
    const double d = (row[k] - row[k - 1]).norm();
    longest = std::max(longest, d);
    length += d;
  }
  const double gap = (row[row.size() - 1] - row[0]).norm();
  return length > 0 && gap <= 2 * longest && gap <= 0.2 * length;
}
}  // namespace

std::string units_of_outputs(const std::string& given, const Input& in) {
  if (given.empty()) return in.units.empty() ? std::string("mm") : in.units;
  if (!in.units.empty() && in.units != given)
    say("warning: " + in.name + " is in " + in.units + " but --units states " + given +
        ": coordinates are not converted, so the outputs are off by the ratio of the units");
  return given;
}

void note_closed_rows(const Input& in, bool& closed_u, bool closed_given, std::string* note) {
  const auto say = [note](const std::string& text) {
    cli::say(text);
    if (note) *note = text;
  };
  if (closed_u || in.rows.size() < 2) return;
  const bool cad_closed =
      !in.closed_rows.empty() &&
      std::all_of(in.closed_rows.begin(), in.closed_rows.end(), [](bool c) { return c; });
  if (cad_closed && !closed_given) {
    closed_u = true;
    say("note: every section curve in " + in.name +
        " is closed: fitting closed rows (--closed u; give --closed none to fit them open)");
    return;
  }
  if (cad_closed) {
    say("warning: every section curve in " + in.name +
        " is closed, but they are fitted open: the surface has a slit where they close");
    return;
  }
  if (closed_given) return;
  for (std::size_t j = 0; j < in.rows.size(); ++j)
    if (!ends_meet(in.rows[j])) return;
  say("warning: the ends of every row of " + in.name +
      " meet: fitted open, the surface has a slit there; give --closed u for closed contours "
      "(first point not repeated), or --closed none to keep them open");
}

}  // namespace sfit::cli
