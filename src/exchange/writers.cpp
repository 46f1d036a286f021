#include "sfit/exchange/writers.h"
#include "sfit/io/file_names.h"
#include "sfit/io/formats.h"

#include <algorithm>

#include "sfit/error.h"
#include "sfit/exchange/cad_writers.h"
#include "sfit/exchange/mesh_writers.h"
#include "sfit/exchange/tessellate.h"

namespace sfit::exchange {

namespace {

Mesh mesh_for(const Surface& s, const WriteOptions& o) {
  check_mesh_density(o.mesh_density);
  if (o.mesh_density != 0) return tessellate(s, o.mesh_density, o.mesh_density);
  const Density d = choose_density(s, default_chord(s, o.tolerance));
  return tessellate(s, d.samples_u, d.samples_v);
}

}  // namespace

void check_mesh_density(int n) {
  if (n != 0 && (n < kMinMeshDensity || n > kMaxMeshDensity))
    throw Error(ErrorCode::kUsage,
                "must be 0 (automatic) or " + std::to_string(kMinMeshDensity) + " ... " +
                    std::to_string(kMaxMeshDensity) + " samples per direction, got " +
                    std::to_string(n),
                Place{.option = "--mesh-density"}, {static_cast<double>(n)});
}

std::vector<std::string> writer_extensions() {
  std::vector<std::string> out;  // from the one format registry (sfit/io/formats.h)
  for (const io::Format& f : io::formats())
    if (f.writes && f.kind == io::FormatKind::kSurface &&
        (f.part == io::FormatPart::kCad || f.part == io::FormatPart::kMesh))
      for (std::string_view e : f.extensions) out.emplace_back(e);
  return out;
}

void write_surface(const std::string& path, const Surface& s, const WriteOptions& o,
                   const FitResult* fit, const Rows* rows) {
  const std::string e = io::extension_of(path);
  CadOptions cad;
  cad.units = o.units;
  if (e == "step" || e == "stp") return write_step(path, s, cad);
  if (e == "igs" || e == "iges") return write_iges(path, s, cad);
  if (e == "obj" && !o.mesh) return write_obj_freeform(path, s);
  if (e == "obj") return write_obj_mesh(path, mesh_for(s, o));
  if (e == "stl") return write_stl(path, mesh_for(s, o));
  if (e == "ply") return write_ply(path, mesh_for(s, o));
  if (e == "vtk" || e == "vts") {
    VtkFields f;
    f.curvature = o.fields;
    if (o.fields) {
      f.fit = fit;
      f.rows = rows;
    }
    const Mesh m = mesh_for(s, o);
    return e == "vtk" ? write_vtk(path, s, m, f) : write_vts(path, s, m, f);
  }
  throw Error(ErrorCode::kUsage,
              "cannot write '" + path + "': unknown output extension '" + e + "'",
              Place{.option = "-o"});
}

}  // namespace sfit::exchange
