#include "api_json.h"

#include <bit>
#include <cmath>
#include <limits>

#include "sfit/error.h"
#include "sfit/io/surface_json.h"
#include "sfit/options.h"
#include "sfit/seam_alignment.h"
#include "surface_json_value.h"

namespace sfit::server {

using nlohmann::json;

namespace {

[[noreturn]] void bad(const std::string& field, const std::string& what) {
  throw Error(ErrorCode::kUsage, what, Place{.option = field});
}

json point_json(const Point& p) {
  return json::array({p.x(), p.y(), p.z()});
}

const json& field(const json& j, const char* name) {
  if (!j.contains(name)) bad(name, "missing");
  return j.at(name);
}

std::size_t index_of(const json& j, const char* name) {
  const json& v = field(j, name);
  if (v.is_number_unsigned()) return v.get<std::size_t>();
  if (v.is_number_integer()) bad(name, "must be >= 0, got " + v.dump());
  bad(name, "must be a whole number >= 0, got " + v.dump());
}

double finite(const json& v, const std::string& name) {
  if (!v.is_number()) bad(name, "must be a number, got " + v.dump());
  const double x = v.get<double>();
  if (!std::isfinite(x)) bad(name, "must be finite, got " + v.dump());
  return x;
}

Point point_of(const json& v, const std::string& name) {
  if (!v.is_array() || v.size() != 3) bad(name, "must be [x, y, z]");
  return Point(finite(v[0], name), finite(v[1], name), finite(v[2], name));
}

std::vector<Point> points_of(const json& j, const char* name) {
  const json& v = field(j, name);
  if (!v.is_array()) bad(name, "must be a list of [x, y, z]");
  std::vector<Point> out;
  out.reserve(v.size());
  for (std::size_t k = 0; k < v.size(); ++k)
    out.push_back(point_of(v[k], std::string(name) + "[" + std::to_string(k) + "]"));
  return out;
}

const char* search_name(CountSearch s) {
  switch (s) {
    case CountSearch::kLinear:
      return "linear";
    case CountSearch::kKnown:
      return "known";
    case CountSearch::kFast:
      break;
  }
  return "fast";
}

void check_keys(const json& j, std::initializer_list<const char*> keys) {
  for (const auto& [k, v] : j.items()) {
    bool known = false;
    for (const char* name : keys) known = known || k == name;
    if (!known) bad(k, "unknown field");
  }
}

// Per-point fraction of T used (max over the axes; at T = 0, of the round-off allowance).
json point_deviations(const FitResult& fit, const Rows& rows) {
  const Point t = fit.report.tolerance;
  const double floor = std::max(fit.report.roundoff, std::numeric_limits<double>::min());
  json out = json::array();
  for (std::size_t j = 0; j < rows.size(); ++j) {
    json row = json::array();
    const std::size_t first = rows.offsets()[j];
    const auto pts = rows[j];
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const Point d =
          (fit.surface.evaluate(fit.u[first + k], fit.point_v(j, first + k)) - pts[k]).cwiseAbs();
      double r = 0;
      for (int a = 0; a < 3; ++a) r = std::max(r, d[a] / std::max(t[a], floor));
      row.push_back(r);
    }
    out.push_back(std::move(row));
  }
  return out;
}

}  // namespace

json error_json(const Error& e) {
  json place = json::object();
  const Place& p = e.place();
  if (!p.file.empty()) place["file"] = p.file;
  if (p.line >= 0) place["line"] = p.line;
  if (p.row >= 0) place["row"] = p.row;
  if (p.point >= 0) place["index"] = p.point;
  if (!p.option.empty()) place["field"] = p.option;
  return json{{"error", format_error_line(p, e.message())},
              {"code", to_string(e.code())},
              {"place", place}};
}

json parse_body(const std::string& body) {
  json j = json::parse(body, nullptr, false);
  if (j.is_discarded()) bad("body", "is not valid JSON");
  if (!j.is_object()) bad("body", "must be a JSON object");
  return j;
}

json options_json(const FitOptions& o) {
  return json{{"tolerance", point_json(o.tolerance)},
              {"degree", {o.degree_u, o.degree_v}},
              {"closed", {o.closed_u, o.closed_v}},
              {"search", search_name(o.search)},
              {"parameters", std::string(to_string(o.parametrization))},
              {"method", std::string(to_string(o.method))},
              {"norm", std::string(to_string(o.norm))},
              {"seam", std::string(to_string(o.seam))},
              {"orient", std::string(to_string(o.orient))},
              {"rerepresent", std::string(to_string(o.rerepresentation))},
              {"knots", std::string(to_string(o.knots))},
              {"fold_guard", o.fold_guard}};
}

namespace {
// The value of `v` for an option of the table, by the table's type.
OptionValue value_of(const OptionSpec& s, const json& v, const std::string& name) {
  switch (s.type) {
    case OptionType::kInteger:
      if (!v.is_number_integer()) bad(name, "must be a whole number, got " + v.dump());
      return v.get<long long>();
    case OptionType::kNumber:
      return finite(v, name);
    case OptionType::kTolerance:
      return v.is_array() ? point_of(v, name) : Point::Constant(finite(v, name));
    case OptionType::kChoice:
      if (!v.is_string()) bad(name, "must be one of " + choice_list(s) + ", got " + v.dump());
      return v.get<std::string>();
    case OptionType::kFlag:
      if (!v.is_boolean()) bad(name, "must be true or false, got " + v.dump());
      return v.get<bool>();
  }
  bad(name, "unknown field");
}
}  // namespace

FitOptions options_from_json(const json& r, const FitOptions& current) {
  // The keys: the option table's fit options (sfit/options.h, GET /api/options-table) that an
  // edit session can change, with tolerance as [Tx, Ty, Tz] or T, degree as [p, q] and closed
  // as [u, v]; every check is the table's (set_fit_option).
  check_keys(r, {"tolerance", "degree", "closed", "search", "parameters", "method", "norm", "seam",
                 "orient", "rerepresent", "knots", "fold_guard", "phase"});
  FitSettings st;
  st.options = current;
  if (r.contains("tolerance")) {
    set_fit_option(st, "tol", value_of(*find_option("tol"), r["tolerance"], "tolerance"),
                   "tolerance");
    st.options.tolerance = *st.tol;
  }
  if (r.contains("degree")) {
    const json& d = r["degree"];
    if (!d.is_array() || d.size() != 2 || !d[0].is_number_integer() || !d[1].is_number_integer())
      bad("degree", "must be [p, q], two whole numbers");
    set_fit_option(st, "degree_u", d[0].get<long long>(), "degree");
    set_fit_option(st, "degree_v", d[1].get<long long>(), "degree");
  }
  if (r.contains("closed")) {
    const json& c = r["closed"];
    if (!c.is_array() || c.size() != 2 || !c[0].is_boolean() || !c[1].is_boolean())
      bad("closed", "must be [u, v], two booleans");
    st.options.closed_u = c[0].get<bool>();
    st.options.closed_v = c[1].get<bool>();
  }
  for (const char* name : {"search", "parameters", "method", "norm", "seam", "orient",
                           "rerepresent", "knots", "fold_guard"})
    if (r.contains(name))
      set_fit_option(st, name, value_of(*find_option(name), r[name], name), name);
  // "known" is the hold's own setting (src/server/hold.cpp), never a request's.
  if (r.contains("search") && st.options.search == CountSearch::kKnown)
    bad("search", "\"known\" needs count hints, which the editor does not give");
  st.options.row_count_hints.clear();
  st.options.column_count_hints.clear();
  return st.options;
}

MovePhase phase_of(const json& r) {
  if (!r.contains("phase")) return MovePhase::kOnce;
  const json& p = r["phase"];
  if (p == "drag") return MovePhase::kDrag;
  if (p == "rest") return MovePhase::kRest;
  if (p == "end") return MovePhase::kEnd;
  if (p != "once") bad("phase", "must be \"drag\", \"rest\", \"end\" or \"once\"");
  return MovePhase::kOnce;
}

void apply_edit(Session& s, const json& r) {
  const json& op = field(r, "op");
  if (!op.is_string()) bad("op", "must be a string");
  const std::string name = op.get<std::string>();
  if (name == "move") {
    check_keys(r, {"op", "row", "index", "to", "phase", "seq"});
    s.move(index_of(r, "row"), index_of(r, "index"), point_of(field(r, "to"), "to"), phase_of(r));
  } else if (name == "insert") {
    check_keys(r, {"op", "row", "index", "point"});
    s.insert_point(index_of(r, "row"), index_of(r, "index"), point_of(field(r, "point"), "point"));
  } else if (name == "delete") {
    check_keys(r, {"op", "row", "index"});
    s.delete_point(index_of(r, "row"), index_of(r, "index"));
  } else if (name == "insert_row") {
    check_keys(r, {"op", "row", "points"});
    s.insert_row(index_of(r, "row"), points_of(r, "points"));
  } else if (name == "delete_row") {
    check_keys(r, {"op", "row"});
    s.delete_row(index_of(r, "row"));
  } else if (name == "replace_row") {
    check_keys(r, {"op", "row", "points"});
    s.replace_row(index_of(r, "row"), points_of(r, "points"));
  } else {
    bad("op", "unknown operation " + op.dump() +
                  " (move, insert, delete, insert_row, delete_row, replace_row)");
  }
}

std::string base64(const unsigned char* data, std::size_t n) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  for (std::size_t i = 0; i < n; i += 3) {
    const unsigned v =
        (data[i] << 16) | ((i + 1 < n ? data[i + 1] : 0) << 8) | (i + 2 < n ? data[i + 2] : 0);
    out += abc[(v >> 18) & 63];
    out += abc[(v >> 12) & 63];
    out += i + 1 < n ? abc[(v >> 6) & 63] : '=';
    out += i + 2 < n ? abc[v & 63] : '=';
  }
  return out;
}

// The surface contract with the control points packed (state_json()).
json packed_surface_json(const Surface& s, Pack pack) {
  static_assert(std::endian::native == std::endian::little, "packed numbers are little-endian");
  json j = io::surface_header_to_json(s);
  const int fu = s.full_count_u(), fv = s.full_count_v();
  std::vector<Point> cp;
  cp.reserve(static_cast<std::size_t>(fu) * fv);
  for (int i = 0; i < fu; ++i)
    for (int l = 0; l < fv; ++l) cp.push_back(s.full_at(i, l));
  j["control_points_shape"] = {fu, fv};
  const auto bytes = [](const auto& v) {
    return base64(reinterpret_cast<const unsigned char*>(v.data()), v.size() * sizeof v[0]);
  };
  if (pack == Pack::kF64) {
    std::vector<double> xyz;
    xyz.reserve(3 * cp.size());
    for (const Point& p : cp) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
    j["control_points_f64"] = bytes(xyz);
    return j;
  }
  Point lo = cp.front(), hi = cp.front();
  for (const Point& p : cp) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Point origin = (lo + hi) / 2;
  std::vector<float> xyz;
  xyz.reserve(3 * cp.size());
  for (const Point& p : cp)
    for (int a = 0; a < 3; ++a) xyz.push_back(static_cast<float>(p[a] - origin[a]));
  j["control_points_origin"] = {origin.x(), origin.y(), origin.z()};
  j["control_points_f32"] = bytes(xyz);
  return j;
}

json state_json(const Session& s, bool with_rows, Pack pack) {
  const FitResult& fit = s.shown();
  const Rows& rows = s.shown_rows();
  const FitReport& r = fit.report;
  double used = 0;
  for (int a = 0; a < 3; ++a)
    used = std::max(used, r.tolerance[a] > 0 ? r.max_deviation[a] / r.tolerance[a]
                                             : (r.max_deviation[a] > r.roundoff ? HUGE_VAL : 0));
  json j;
  j["version"] = s.version();
  j["final"] = s.final();
  j["dragging"] = s.dragging();
  j["checked"] = r.points == rows.total_points();
  j["surface"] = pack == Pack::kNone ? io::surface_to_json(fit.surface)
                                     : packed_surface_json(fit.surface, pack);
  j["report"] = io::report_to_json(r);
  j["deviation"] = {{"max", point_json(r.max_deviation)},
                    {"tolerance", point_json(r.tolerance)},
                    {"used", std::isfinite(used) ? json(used) : json(nullptr)},
                    {"within", r.within_tolerance}};
  j["options"] = options_json(s.options());
  j["undo"] = s.undo_depth();
  j["redo"] = s.redo_depth();
  j["rows_refitted"] = s.rows_refitted();
  // No surface within T was found (the file opened, or an edit left it, so): the best one
  // found is shown, and why the search failed.
  j["best_effort"] = s.best_effort().empty() ? json(nullptr) : json(s.best_effort());
  j["points"] = rows.total_points();
  if (with_rows) {
    json rj = json::array();
    for (std::size_t k = 0; k < rows.size(); ++k) {
      json row = json::array();
      for (const Point& p : rows[k]) row.push_back(point_json(p));
      rj.push_back(std::move(row));
    }
    j["rows"] = std::move(rj);
    j["point_deviation"] = point_deviations(fit, rows);
    json u = json::array();
    for (std::size_t k = 0; k < rows.size(); ++k)
      u.push_back(
          std::vector<double>(fit.u.begin() + static_cast<std::ptrdiff_t>(rows.offsets()[k]),
                              fit.u.begin() + static_cast<std::ptrdiff_t>(rows.offsets()[k + 1])));
    j["u"] = std::move(u);
    j["v"] = fit.v;
    if (!fit.v_points.empty()) {  // parameters geometric: each point's own v, by row as u
      json vp = json::array();
      for (std::size_t k = 0; k < rows.size(); ++k)
        vp.push_back(std::vector<double>(
            fit.v_points.begin() + static_cast<std::ptrdiff_t>(rows.offsets()[k]),
            fit.v_points.begin() + static_cast<std::ptrdiff_t>(rows.offsets()[k + 1])));
      j["v_points"] = std::move(vp);
    }
  }
  return j;
}

}  // namespace sfit::server
