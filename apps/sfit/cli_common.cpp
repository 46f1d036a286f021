#include "cli_common.h"
#include "outputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "sfit/error.h"
#include "sfit/fit_limits.h"
#include "sfit/io/file_names.h"
#include "sfit/io/formats.h"
#include "sfit/option_names.h"
#include "sfit/options.h"

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

const OptionSpec& option_spec(std::string_view name) {
  const OptionSpec* s = find_option(name);
  if (!s) throw Error(ErrorCode::kInternal, "no option " + std::string(name) + " in the table");
  return *s;
}

int table_default_int(std::string_view name) {
  return std::stoi(std::string(option_spec(name).default_value));
}

std::string option_help(std::string_view name) {
  return full_help(option_spec(name));
}

CLI::Option* add_table_option(CLI::App* c, std::string_view name, std::string& value) {
  const OptionSpec& s = option_spec(name);
  CLI::Option* o = c->add_option(std::string(s.flag), value, full_help(s));
  // The fit's choices are checked here; the output options by their writers (whose messages
  // name the known values too).
  if (s.type == OptionType::kChoice && s.group == OptionGroup::kFit) {
    std::vector<std::string> allowed(s.choices.begin(), s.choices.end());
    o->check(CLI::Validator(  // before the choices: an empty value says so (harden_options)
        [](std::string& v) { return v.empty() ? std::string("empty value") : std::string(); }, "",
        "non-empty"));
    o->check(CLI::IsMember(allowed));
  }
  return o;
}

CLI::Option* add_table_flag(CLI::App* c, std::string_view name, bool& value) {
  const OptionSpec& s = option_spec(name);
  return c->add_flag(std::string(s.flag), value, full_help(s));
}

void add_fit_option_flags(CLI::App* c, FitOptionArgs& a) {
  // The flags, their help, allowed values and defaults: the library's option table
  // (sfit/options.h), in its order; only the binding to FitOptionArgs is here.
  for (const OptionSpec& s : option_table()) {
    if (s.group != OptionGroup::kFit) continue;
    const std::string flag(s.flag), help = full_help(s);
    const std::string_view n = s.name;
    if (n == "degree") {
      c->add_option(flag, a.degree, help);
    } else if (n == "degree_u") {
      c->add_option(flag, a.degree_u, help);
    } else if (n == "degree_v") {
      c->add_option(flag, a.degree_v, help);
    } else if (n == "tol") {
      c->add_option(flag, a.tol, help);
    } else if (n == "tol_rel") {
      c->add_option(flag, a.tol_rel, help);
    } else if (n == "threads") {
      c->add_option(flag, a.threads, help);
    } else if (n == "fold_guard") {
      c->add_flag(flag, a.no_fold_guard, help);
    } else if (s.type == OptionType::kChoice) {
      std::string& value = a.choices[std::string(n)];
      if (n != "closed") value = s.default_value;  // closed: "" is "not given"
      add_table_option(c, n, value);
    } else {
      throw Error(ErrorCode::kInternal, "the CLI binds no flag for option " + std::string(n));
    }
  }
}

CheckedFitOptions check_fit_options(const FitOptionArgs& a) {
  // Every check is the library's (set_fit_option: the table's limits and allowed values).
  FitSettings st;
  set_fit_option(st, "degree", static_cast<long long>(a.degree), "--degree");
  if (a.degree_u) set_fit_option(st, "degree_u", static_cast<long long>(*a.degree_u), "--degree-u");
  if (a.degree_v) set_fit_option(st, "degree_v", static_cast<long long>(*a.degree_v), "--degree-v");
  for (const auto& [name, value] : a.choices) {
    const std::string flag(option_spec(name).flag);
    if (!value.empty()) set_fit_option(st, name, value, flag);
  }
  // "known" (counts given as the answer) is for callers with count hints.
  if (st.options.search == CountSearch::kKnown)
    throw Error(ErrorCode::kUsage,
                "'known' takes count hints as the answer, which the command line does not give",
                Place{.option = "--search"});
  set_fit_option(st, "fold_guard", !a.no_fold_guard, "--no-fold-guard");
  set_fit_option(st, "threads", static_cast<long long>(a.threads), "--threads");
  if (a.tol && a.tol_rel)
    throw Error(ErrorCode::kUsage, "give --tol or --tol-rel, not both",
                Place{.option = "--tol-rel"});
  if (a.tol_rel) set_fit_option(st, "tol_rel", *a.tol_rel, "--tol-rel");
  if (a.tol) set_fit_option(st, "tol", parse_tolerance(*a.tol, "--tol"), "--tol");
  CheckedFitOptions c;
  c.options = st.options;
  c.fraction = st.tol_rel.value_or(kDefaultToleranceFraction);
  if (st.tol) c.absolute = *st.tol;
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
  Input in = files::read_input(path);
  if (!in.units.empty())  // STEP/IGES
    say(path + ": lengths in " + in.units +
        (in.units.find(' ') == std::string::npos ? " (the file's own unit, not converted)" : ""));
  return in;
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

void add_output_shape_options(CLI::App* c, OutputShapeArgs& a) {
  add_table_flag(c, "mesh", a.mesh);
  add_table_flag(c, "obj_freeform", a.obj_freeform);
  c->add_option("--mesh-density", a.mesh_density, option_help("mesh_density"));
  add_table_option(c, "normals", a.normals);
  add_table_flag(c, "fields", a.fields);
  add_table_option(c, "units", a.units);
}

files::OutputContext output_context(const OutputShapeArgs& a, const Surface& surface,
                                    const FitResult* fit, const Rows* rows,
                                    const std::string& input, const std::string& units) {
  files::OutputContext ctx{surface, fit, rows, input, a.mesh, a.mesh_density, a.fields, units};
  ctx.obj_freeform = a.obj_freeform;
  ctx.normals = a.normals;
  return ctx;
}

}  // namespace sfit::cli
