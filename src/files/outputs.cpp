// The writers of sfit/files.h: JSON always, the other surface formats of the registry that
// this build has through the exchange part.
#include "sfit/files.h"

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

namespace sfit::files {
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
    // Every other surface format of the registry (sfit/io/formats.h) this build has.
    for (const io::Format& f : io::formats()) {
      if (!f.writes || f.kind != io::FormatKind::kSurface || f.part == io::FormatPart::kCore ||
          !f.available)
        continue;
      for (std::string_view ext : f.extensions)
        m[std::string(ext)] = [](const std::string& p, const OutputContext& c) {
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
  for (const auto& [ext, writer] : writers()) v.push_back(ext);
  return v;
}

void check_output_extension(const std::string& path, const std::string& option,
                            io::FormatKind kind) {
  const std::string e = io::extension_of(path);
  const io::Format* f = io::find_format(e);
  if (f && f->kind == kind && f->writes && f->available &&
      (kind != io::FormatKind::kSurface || writers().count(e))) {
#ifdef SFIT_HAVE_EXCHANGE
    if (f->part == io::FormatPart::kCad) exchange::require_cad(option);  // before any work
#endif
    return;
  }
  if (f && f->kind == kind && f->writes)
    throw Error(ErrorCode::kUsage,
                "cannot write '" + path + "': " + std::string(f->name) + " needs " +
                    std::string(io::part_name(f->part)) + ", which this build of sfit lacks",
                Place{.option = option});
  throw Error(ErrorCode::kUsage,
              "cannot write '" + path + "': unknown output extension '" + e +
                  "' (known: " + io::extension_list(kind, false) + ")",
              Place{.option = option});
}

void check_output_options(const std::string& units, int mesh_density, const std::string& normals) {
#ifdef SFIT_HAVE_EXCHANGE
  exchange::check_units(units);
  exchange::check_mesh_density(mesh_density);
  exchange::parse_normal_rule(normals);
#else
  (void)units;
  (void)mesh_density;
  (void)normals;
#endif
}

std::string write_output(const std::string& path, const OutputContext& context, std::string* text) {
  if (text) {
    *text = io::surface_json_text(context.surface, context.fit ? &context.fit->report : nullptr);
    return {};
  }
  check_output_extension(path);
  return writers().at(io::extension_of(path))(path, context);
}

}  // namespace sfit::files
