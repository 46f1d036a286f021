// Setting an option of the table (sfit/options.h) from a front end's value: the checks of
// type, range and allowed values, once for the CLI, Python and the editor.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sfit/error.h"
#include "sfit/option_names.h"
#include "sfit/options.h"
#include "sfit/parametrization.h"
#include "sfit/seam_alignment.h"

namespace sfit {

namespace {

[[noreturn]] void usage(const std::string& place, const std::string& what) {
  throw Error(ErrorCode::kUsage, what, Place{.option = place});
}

std::string g(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

std::string shown(const OptionValue& v) {
  if (auto* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  if (auto* i = std::get_if<long long>(&v)) return std::to_string(*i);
  if (auto* d = std::get_if<double>(&v)) return g(*d);
  if (auto* s = std::get_if<std::string>(&v)) return "'" + *s + "'";
  const Point& p = std::get<Point>(v);
  return "(" + g(p.x()) + ", " + g(p.y()) + ", " + g(p.z()) + ")";
}

const OptionSpec& spec_of(std::string_view name, OptionGroup group, const std::string& place) {
  const OptionSpec* s = find_option(name);
  if (s && s->group == group) return *s;
  std::string known;
  for (const OptionSpec& o : option_table())
    if (o.group == group) known += (known.empty() ? "" : ", ") + std::string(o.name);
  usage(place, "unknown option (known: " + known + ")");
}

long long integer(const OptionValue& v, const std::string& place) {
  if (auto* i = std::get_if<long long>(&v)) return *i;
  usage(place, "expected a whole number, got " + shown(v));
}

double number(const OptionValue& v, const std::string& place) {
  if (auto* i = std::get_if<long long>(&v)) return static_cast<double>(*i);
  if (auto* d = std::get_if<double>(&v)) return *d;
  usage(place, "expected a number, got " + shown(v));
}

bool flag(const OptionValue& v, const std::string& place) {
  if (auto* b = std::get_if<bool>(&v)) return *b;
  usage(place, "expected true or false, got " + shown(v));
}

// The value of a kChoice option, one of the table's choices (the message lists them all).
std::string choice(const OptionSpec& s, const OptionValue& v, const std::string& place) {
  const std::string* t = std::get_if<std::string>(&v);
  if (!t) usage(place, "expected one of " + choice_list(s) + ", got " + shown(v));
  for (std::string_view c : s.choices)
    if (*t == c) return *t;
  usage(place, "'" + *t + "' is not one of " + choice_list(s));
}

template <class E>
E parsed(const std::string& text, bool (*parse)(std::string_view, E&), const std::string& place) {
  E out{};
  if (!parse(text, out)) usage(place, "'" + text + "' has no meaning here");  // table vs parser
  return out;
}

int ranged(const OptionSpec& s, const OptionValue& v, const std::string& place) {
  const long long x = integer(v, place);
  if (s.name == "degree" || s.name == "degree_u" || s.name == "degree_v") {
    check_degree(static_cast<int>(std::clamp<long long>(x, -1, 1000)), place);
  } else if (s.name == "threads") {
    check_threads(static_cast<int>(std::clamp<long long>(x, -1, 1000000)), place);
  } else if (!(x == 0 && s.name == "mesh_density") && (x < s.min || x > s.max)) {
    usage(place, "must be " + std::string(s.name == "mesh_density" ? "0 (automatic) or " : "") +
                     g(s.min) + " ... " + g(s.max) +
                     (s.name == "mesh_density" ? " samples per direction" : "") + ", got " +
                     std::to_string(x));
  }
  return static_cast<int>(x);
}

}  // namespace

Point FitSettings::tolerance(const Rows& rows) const {
  return tol ? *tol : relative_tolerance(rows, tol_rel.value_or(kDefaultToleranceFraction));
}

void set_fit_option(FitSettings& st, std::string_view name, const OptionValue& v,
                    const std::string& place) {
  const OptionSpec& s = spec_of(name, OptionGroup::kFit, place);
  FitOptions& o = st.options;
  if (s.type == OptionType::kInteger) {
    const int x = ranged(s, v, place);
    if (name == "degree") o.degree_u = o.degree_v = x;
    if (name == "degree_u") o.degree_u = x;
    if (name == "degree_v") o.degree_v = x;
    if (name == "threads") o.threads = x;
  } else if (name == "tol") {
    Point t;
    if (auto* p = std::get_if<Point>(&v))
      t = *p;
    else
      t = Point::Constant(number(v, place));
    check_tolerance(t, place);
    st.tol = t;
  } else if (name == "tol_rel") {
    const double f = number(v, place);
    check_tolerance_fraction(f, place);
    st.tol_rel = f;
  } else if (name == "fold_guard") {
    o.fold_guard = flag(v, place);
  } else if (name == "closed" && std::holds_alternative<std::string>(v) &&
             parse_closed(std::get<std::string>(v), o.closed_u, o.closed_v)) {
    // the table's choices and parse_closed()'s spellings of them: "" (none) and "vu" (uv)
  } else {
    const std::string c = choice(s, v, place);
    if (name == "closed") parse_closed(c, o.closed_u, o.closed_v);
    if (name == "search") o.search = parsed(c, parse_count_search, place);
    if (name == "parameters") o.parametrization = parsed(c, parse_parametrization, place);
    if (name == "knots") o.knots = parsed(c, parse_knot_rule, place);
    if (name == "method") o.method = parsed(c, parse_fit_method, place);
    if (name == "norm") o.norm = parsed(c, parse_fit_norm, place);
    if (name == "seam") o.seam = parsed(c, parse_seam_mode, place);
    if (name == "orient") o.orient = parsed(c, parse_orient_mode, place);
    if (name == "rerepresent") o.rerepresentation = parsed(c, parse_resampling, place);
  }
}

void set_output_option(OutputSettings& st, std::string_view name, const OptionValue& v,
                       const std::string& place) {
  const OptionSpec& s = spec_of(name, OptionGroup::kOutput, place);
  if (name == "mesh") st.mesh = flag(v, place);
  if (name == "obj_freeform") st.obj_freeform = flag(v, place);
  if (name == "fields") st.fields = flag(v, place);
  if (name == "mesh_density") st.mesh_density = ranged(s, v, place);
  if (name == "normals") st.normals = choice(s, v, place);
  if (name == "units") st.units = choice(s, v, place);
}

}  // namespace sfit
