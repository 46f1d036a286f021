#include "surface_json_value.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "input_file.h"
#include "sfit/error.h"
#include "sfit/fit_limits.h"
#include "sfit/io/atomic_file.h"

namespace sfit::io {

using nlohmann::json;

namespace {
json point(const Point& p) {
  return json::array({p.x(), p.y(), p.z()});
}
}  // namespace

json surface_header_to_json(const Surface& s) {
  json j;
  j["type"] = "bspline_surface";
  if (s.non_uniform()) j["version"] = kNonUniformVersion;  // uniform files stay version 1
  j["degree"] = {s.degree_u, s.degree_v};
  j["periodic"] = {s.periodic_u, s.periodic_v};
  j["knots_u"] = s.full_knots_u();
  j["knots_v"] = s.full_knots_v();
  return j;
}

json surface_to_json(const Surface& s) {
  json j = surface_header_to_json(s);
  json cps = json::array();
  const int fu = s.full_count_u(), fv = s.full_count_v();
  for (int i = 0; i < fu; ++i) {
    json row = json::array();
    for (int l = 0; l < fv; ++l) row.push_back(point(s.full_at(i, l)));
    cps.push_back(std::move(row));
  }
  j["control_points"] = std::move(cps);
  return j;
}

json report_to_json(const FitReport& r) {
  json j;
  j["points"] = r.points;
  j["rows"] = r.rows;
  j["tolerance"] = point(r.tolerance);
  j["max_deviation"] = point(r.max_deviation);
  j["worst"] = {
      {"row", r.worst_row}, {"index", r.worst_index}, {"deviation", point(r.worst_deviation)}};
  j["within_tolerance"] = r.within_tolerance;
  j["control_points"] = {r.count_u, r.count_v};
  j["row_counts"] = r.row_counts;
  j["seconds"] = r.seconds;
  // sfit's extras.
  j["degree"] = {r.degree_u, r.degree_v};
  j["closed"] = {r.closed_u, r.closed_v};
  j["parameters"] = std::string(to_string(r.parametrization));
  j["column_counts"] = r.column_counts;
  j["raised"] = {r.raised_u, r.raised_v};
  j["repaired"] = {r.repaired_rows, r.repaired_columns};
  j["tightenings"] = r.tightenings;
  j["solves"] = r.solves;
  j["roundoff"] = r.roundoff;
  j["method"] = std::string(to_string(r.method));
  j["norm"] = std::string(to_string(r.norm));
  j["pairs_tried"] = r.pairs_tried;
  j["stop_reason"] = r.stop_reason;
  // Seams and shape measures (docs/seams.md): rows re-ordered, [row, shift, reversed, offset].
  json seams = json::array();
  for (std::size_t k = 0; k < r.seams.size(); ++k)
    if (r.seams[k].shift != 0 || r.seams[k].reversed || r.seams[k].offset != 0)
      seams.push_back({k, r.seams[k].shift, r.seams[k].reversed, r.seams[k].offset});
  j["seams"] = std::move(seams);
  j["box_excursion"] = r.box_excursion;
  j["fold"] = r.fold;
  j["parameters_across"] = std::string(to_string(r.parametrization_across));
  j["row_gap"] = r.row_gap;
  j["knots"] = std::string(to_string(r.knots));
  return j;
}

namespace {

[[noreturn]] void bad(const std::string& name, const std::string& what) {
  throw Error(ErrorCode::kInputData, "not an sfit surface: " + what, Place{.file = name});
}

// The direction's knots (validated) and its distinct control-point count.
KnotVector read_knots(const json& j, const std::string& name, const char* key, int degree,
                      bool periodic, std::size_t full, int& count) {
  const auto& k = j.at(key);
  if (!k.is_array() || k.size() != full + degree + 1)
    bad(name, std::string(key) + " must have " + std::to_string(full + degree + 1) + " entries");
  count = static_cast<int>(full) - (periodic ? degree : 0);
  if (count < degree + 1) bad(name, std::string("too few control points along ") + key);
  std::vector<double> values(k.size());
  for (std::size_t i = 0; i < k.size(); ++i) {
    if (!k[i].is_number())
      bad(name, std::string(key) + " entry " + std::to_string(i) + " is not a number");
    values[i] = k[i].get<double>();
  }
  try {
    return KnotVector::from_full(degree, periodic, std::move(values), key);
  } catch (const Error& e) {
    bad(name, e.what());
  }
}

}  // namespace

Surface surface_from_json(const json& j, const std::string& name) {
  try {
    if (!j.is_object() || j.value("type", "") != "bspline_surface")
      bad(name, "\"type\" must be \"bspline_surface\"");
    Surface s;
    auto degree = [&](int k) {
      const json& d = j.at("degree").at(k);
      if (!d.is_number_integer() || d.get<long long>() < 1 || d.get<long long>() > kMaxFitDegree)
        bad(name, "degrees must be whole numbers 1 ... " + std::to_string(kMaxFitDegree));
      return static_cast<int>(d.get<long long>());
    };
    s.degree_u = degree(0);
    s.degree_v = degree(1);
    if (j.contains("periodic")) {
      s.periodic_u = j.at("periodic").at(0).get<bool>();
      s.periodic_v = j.at("periodic").at(1).get<bool>();
    }
    const auto& cps = j.at("control_points");
    if (!cps.is_array() || cps.empty() || !cps[0].is_array() || cps[0].empty())
      bad(name, "control_points must be a non-empty nu x nv array");
    const std::size_t fu = cps.size(), fv = cps[0].size();
    if (j.contains("version")) {
      const json& v = j.at("version");
      if (!v.is_number_integer() || v.get<long long>() < 1 ||
          v.get<long long>() > kNonUniformVersion)
        bad(name, "contract version must be 1 ... " + std::to_string(kNonUniformVersion) +
                      " (a newer sfit wrote it?)");
    }
    KnotVector ku = read_knots(j, name, "knots_u", s.degree_u, s.periodic_u, fu, s.count_u);
    KnotVector kv = read_knots(j, name, "knots_v", s.degree_v, s.periodic_v, fv, s.count_v);
    s.set_knots_u(std::move(ku));
    s.set_knots_v(std::move(kv));
    s.control.resize(static_cast<std::size_t>(s.count_u) * s.count_v);
    for (std::size_t i = 0; i < fu; ++i) {
      if (!cps[i].is_array() || cps[i].size() != fv)
        bad(name, "control_points rows differ in length");
      for (std::size_t l = 0; l < fv; ++l) {
        const auto& c = cps[i][l];
        if (!c.is_array() || c.size() != 3) bad(name, "a control point must be [x, y, z]");
        const Point p(c[0].get<double>(), c[1].get<double>(), c[2].get<double>());
        if (!p.allFinite()) bad(name, "a control point is not finite");
        const int di = static_cast<int>(i) % s.count_u, dl = static_cast<int>(l) % s.count_v;
        if (static_cast<int>(i) < s.count_u && static_cast<int>(l) < s.count_v) {
          s.at(di, dl) = p;
        } else if ((s.at(di, dl) - p).norm() > 1e-12 * (1 + p.norm())) {
          bad(name, "a periodic direction's repeated control points differ from the first ones");
        }
      }
    }
    return s;
  } catch (const json::exception& e) {
    bad(name, e.what());
  }
}

json read_json_file(const std::string& path) {
  std::uint64_t size = 0;
  const detail::InputFile f = detail::open_input(path, &size);
  std::string text;
  char buf[1 << 16];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f.get())) > 0;) text.append(buf, n);
  if (std::ferror(f.get()))
    throw Error(ErrorCode::kInputUnreadable, "cannot read input: read error", Place{.file = path});
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(ErrorCode::kInputSyntax, std::string("malformed JSON: ") + e.what(),
                Place{.file = path});
  } catch (const json::exception& e) {  // 406: number overflow (1e999)
    throw Error(ErrorCode::kInputData,
                std::string("a number is out of the range of a double: ") + e.what(),
                Place{.file = path});
  }
}

Surface read_surface_json(const std::string& path) {
  return surface_from_json(read_json_file(path), path);
}

namespace {
// surface_to_json() (with the report) as json::dump() writes it, a row of control points at a
// time: no tree of every control point and no whole text in memory (on a 1000 x 1000 surface
// those took 72 and 94 MB, more than the fit). The keys are sorted, so "control_points" comes
// first; the rest is the header's dump after its '{'.
void dump_surface_json(std::ostream& out, const Surface& s, const FitReport* report) {
  json rest = surface_header_to_json(s);
  if (report) rest["report"] = report_to_json(*report);
  const std::string tail = rest.dump();
  out << "{\"control_points\":[";
  const int fu = s.full_count_u(), fv = s.full_count_v();
  for (int i = 0; i < fu; ++i) {
    json row = json::array();
    for (int l = 0; l < fv; ++l) row.push_back(point(s.full_at(i, l)));
    if (i > 0) out << ',';
    out << row.dump();
  }
  out << "]," << std::string_view(tail).substr(1) << '\n';
}
}  // namespace

std::string surface_json_text(const Surface& surface, const FitReport* report) {
  std::ostringstream out;
  dump_surface_json(out, surface, report);
  return std::move(out).str();
}

std::string surface_to_json_text(const Surface& surface, const FitReport* report, int indent) {
  json j = surface_to_json(surface);
  if (report) j["report"] = report_to_json(*report);
  return j.dump(indent);
}

std::string report_to_json_text(const FitReport& report, int indent) {
  return report_to_json(report).dump(indent);
}

Surface surface_from_json_text(std::string_view text, const std::string& name) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(ErrorCode::kInputSyntax, std::string("malformed JSON: ") + e.what(),
                Place{.file = name});
  }
  return surface_from_json(j, name);
}

void write_surface_json(const std::string& path, const Surface& surface, const FitReport* report) {
  write_file_atomically(path, [&](std::ostream& out) { dump_surface_json(out, surface, report); });
}

void write_report_json(const std::string& path, const FitReport& report) {
  write_file_atomically(path,
                        [&](std::ostream& out) { out << report_to_json(report).dump(2) << '\n'; });
}

}  // namespace sfit::io
