#include "sfit/io/report_json.h"

#include <nlohmann/json.hpp>

#include "sfit/error.h"
#include "sfit/parametrization.h"

namespace sfit::io {

using nlohmann::json;

namespace {

[[noreturn]] void bad(const std::string& name, const std::string& what) {
  throw Error(ErrorCode::kInputData, "not an sfit report: " + what, Place{.file = name});
}

Point point(const json& j) {
  return Point(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>());
}

template <class T>
void named(const json& j, const char* key, T& out, bool (*parse)(std::string_view, T&),
           const std::string& name) {
  if (!parse(j.at(key).get<std::string>(), out)) bad(name, std::string("unknown \"") + key + "\"");
}

}  // namespace

FitReport report_from_json_text(std::string_view text, const std::string& name) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(ErrorCode::kInputSyntax, std::string("malformed JSON: ") + e.what(),
                Place{.file = name});
  }
  FitReport r;
  const char* key = "";
  try {
    if (!j.is_object()) bad(name, "not a JSON object");
    key = "points";
    r.points = j.at(key).get<std::size_t>();
    key = "rows";
    r.rows = j.at(key).get<std::size_t>();
    key = "tolerance";
    r.tolerance = point(j.at(key));
    key = "max_deviation";
    r.max_deviation = point(j.at(key));
    key = "worst";
    r.worst_row = j.at(key).at("row").get<long>();
    r.worst_index = j.at(key).at("index").get<long>();
    r.worst_deviation = point(j.at(key).at("deviation"));
    key = "within_tolerance";
    r.within_tolerance = j.at(key).get<bool>();
    key = "control_points";
    r.count_u = j.at(key).at(0).get<int>();
    r.count_v = j.at(key).at(1).get<int>();
    key = "row_counts";
    r.row_counts = j.at(key).get<std::vector<int>>();
    key = "seconds";
    r.seconds = j.at(key).get<double>();
    key = "degree";
    r.degree_u = j.at(key).at(0).get<int>();
    r.degree_v = j.at(key).at(1).get<int>();
    key = "closed";
    r.closed_u = j.at(key).at(0).get<bool>();
    r.closed_v = j.at(key).at(1).get<bool>();
    key = "parameters";
    named(j, key, r.parametrization, parse_parametrization, name);
    key = "column_counts";
    r.column_counts = j.at(key).get<std::vector<int>>();
    key = "raised";
    r.raised_u = j.at(key).at(0).get<int>();
    r.raised_v = j.at(key).at(1).get<int>();
    key = "repaired";
    r.repaired_rows = j.at(key).at(0).get<int>();
    r.repaired_columns = j.at(key).at(1).get<int>();
    key = "tightenings";
    r.tightenings = j.at(key).get<int>();
    key = "solves";
    r.solves = j.at(key).get<long>();
    key = "roundoff";
    r.roundoff = j.at(key).get<double>();
    key = "method";
    named(j, key, r.method, parse_fit_method, name);
    key = "norm";
    named(j, key, r.norm, parse_fit_norm, name);
    key = "pairs_tried";
    r.pairs_tried = j.at(key).get<long>();
    key = "stop_reason";
    r.stop_reason = j.at(key).get<std::string>();
    key = "seams";
    const json& seams = j.at(key);
    if (!seams.empty()) {
      r.seams.assign(r.rows, RowSeam{});
      for (const json& s : seams) {
        const auto row = s.at(0).get<std::size_t>();
        if (row >= r.rows) bad(name, "a seam names row " + std::to_string(row));
        r.seams[row] = RowSeam{s.at(1).get<long>(), s.at(2).get<bool>(), s.at(3).get<double>()};
      }
    }
    key = "box_excursion";
    r.box_excursion = j.at(key).get<double>();
    key = "fold";
    r.fold = j.at(key).get<double>();
    key = "parameters_across";
    named(j, key, r.parametrization_across, parse_parametrization, name);
    key = "row_gap";
    r.row_gap = j.at(key).get<double>();
    key = "knots";  // written since knot vectors are data; older reports: uniform
    if (j.contains(key)) named(j, key, r.knots, parse_knot_rule, name);
  } catch (const json::exception&) {
    bad(name, std::string("\"") + key + "\" is missing or of the wrong type");
  }
  return r;
}

}  // namespace sfit::io
