#include "sfit/exchange/writers.h"

#include <cstdio>

#include "sfit/error.h"
#include "sfit/exchange/cad_writers.h"
#include "sfit/exchange/mesh_writers.h"
#include "sfit/exchange/tessellate.h"
#include "sfit/io/file_names.h"
#include "sfit/io/formats.h"

namespace sfit::exchange {

namespace {

std::string describe(const Mesh& m, bool quads) {
  std::string d = std::string(quads ? "quad mesh, " : "triangle mesh, ") +
                  std::to_string(m.samples_u) + " x " + std::to_string(m.samples_v) + " samples, " +
                  std::to_string(m.triangles.size() / (quads ? 2 : 1)) +
                  (quads ? " quads" : " triangles");
  if (m.chordal_bound >= 0) {
    char b[48];
    std::snprintf(b, sizeof b, ", chordal error <= %.3g", m.chordal_bound);
    d += b;
  }
  return d + ", normals " + m.orientation;
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

void check_write_options(const WriteOptions& o) {
  check_mesh_density(o.mesh_density);
  check_units(o.units);
}

std::string write_surface(const std::string& path, const Surface& s, const WriteOptions& o,
                          const FitResult* fit, const Rows* rows) {
  check_write_options(o);
  const std::string e = io::extension_of(path);
  CadOptions cad;
  cad.units = o.units;
  const std::string exact = "B-spline surface, " + std::to_string(s.count_u) + " x " +
                            std::to_string(s.count_v) + " control points, degree " +
                            std::to_string(s.degree_u) + " x " + std::to_string(s.degree_v);
  if (e == "step" || e == "stp") {
    write_step(path, s, cad);
    return exact + ", units " + o.units;
  }
  if (e == "igs" || e == "iges") {
    write_iges(path, s, cad);
    return exact + ", units " + o.units;
  }
  if (e == "obj" && o.obj_freeform) {
    write_obj_freeform(path, s);
    return "free-form " + exact +
           " (most mesh viewers show no surface: drop --obj-freeform "
           "for a triangle mesh)";
  }
  const auto mesh = [&] { return make_mesh(s, o.mesh_density, o.tolerance, o.normals); };
  if (e == "obj" || e == "stl" || e == "ply") {
    const Mesh m = mesh();
    if (e == "obj") write_obj_mesh(path, m);
    if (e == "stl") write_stl(path, m);
    if (e == "ply") write_ply(path, m);
    return describe(m, false);
  }
  if (e == "vtk" || e == "vts") {
    VtkFields f;
    f.curvature = o.fields;
    if (o.fields) {
      f.fit = fit;
      f.rows = rows;
    }
    const Mesh m = mesh();
    if (e == "vtk")
      write_vtk(path, s, m, f);
    else
      write_vts(path, s, m, f);
    std::string d = describe(m, true);
    if (o.fields)
      d += std::string(", fields: curvature") +
           (fit && rows ? ", deviation" : " (no deviation: no fit data)");
    return d;
  }
  throw Error(ErrorCode::kUsage,
              "cannot write '" + path + "': unknown output extension '" + e + "'",
              Place{.option = "-o"});
}

}  // namespace sfit::exchange
