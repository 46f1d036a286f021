#include "outputs.h"

#include <algorithm>
#include <map>

#include "sfit/error.h"
#include "sfit/io/file_names.h"
#include "sfit/io/surface_json.h"
#ifdef SFIT_HAVE_EXCHANGE
#include "sfit/exchange/cad_writers.h"
#include "sfit/exchange/tessellate.h"
#include "sfit/exchange/writers.h"
#endif

namespace sfit::cli {
namespace {

using Writer = std::function<std::string(const std::string&, const OutputContext&)>;

const std::map<std::string, Writer>& writers() {
  static const std::map<std::string, Writer> w = [] {
    std::map<std::string, Writer> m;
    m["json"] = [](const std::string& p, const OutputContext& c) {
      io::write_surface_json(p, c.surface, c.fit ? &c.fit->report : nullptr);
      return std::string();
    };
#ifdef SFIT_HAVE_EXCHANGE
    for (const auto& ext : exchange::writer_extensions()) {
      m[ext] = [](const std::string& p, const OutputContext& c) {
        exchange::WriteOptions o;
        o.mesh = c.mesh;
        o.obj_freeform = c.obj_freeform;
        o.normals = exchange::parse_normal_rule(c.normals);
        o.mesh_density = c.mesh_density;
        o.fields = c.fields;
        o.units = c.units;
        o.tolerance = c.fit ? c.fit->report.tolerance.minCoeff() : 0.0;
        return exchange::write_surface(p, c.surface, o, c.fit, c.rows);
      };
    }
#endif
    return m;
  }();
  return w;
}

}  // namespace

std::vector<std::string> output_extensions() {
  std::vector<std::string> v;
  for (const auto& [k, w] : writers()) v.push_back(k);
  return v;
}

void check_output_extension(const std::string& path) {
  const std::string e = extension_of(path);
  if (writers().count(e)) return;
  std::string known;
  for (const auto& k : output_extensions()) known += (known.empty() ? "." : ", .") + k;
  throw Error(
      ErrorCode::kUsage,
      "cannot write '" + path + "': unknown output extension '" + e + "' (known: " + known + ")",
      Place{.option = "-o"});
}

void check_units(const std::string& units) {
#ifdef SFIT_HAVE_EXCHANGE
  exchange::check_units(units);
#else
  (void)units;
#endif
}

void check_mesh_options(int mesh_density, const std::string& normals) {
#ifdef SFIT_HAVE_EXCHANGE
  exchange::check_mesh_density(mesh_density);
  exchange::parse_normal_rule(normals);
#else
  (void)mesh_density;
  (void)normals;
#endif
}

std::string write_output(const std::string& path, const OutputContext& context) {
  check_output_extension(path);
  return writers().at(extension_of(path))(path, context);
}

}  // namespace sfit::cli
