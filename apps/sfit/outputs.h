// Output formats chosen by the -o extension. The JSON contract is built in; optional parts
// (exchange, render) register theirs in outputs.cpp under their SFIT_HAVE_* switch.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sfit/io/file_names.h"
#include "sfit/rows.h"
#include "sfit/surface.h"
#include "sfit/surface_fit.h"

namespace sfit::cli {

/// What a writer may use: the surface always; the fit and the data when the command fitted.
struct OutputContext {
  const Surface& surface;
  const FitResult* fit = nullptr;
  const Rows* rows = nullptr;
  std::string input_name;
  bool mesh = false;         ///< --mesh: OBJ as a tessellated mesh instead of free-form
  int mesh_density = 0;      ///< --mesh-density: samples per direction (0: automatic)
  bool fields = false;       ///< --fields: deviation/curvature point data (VTK)
  std::string units = "mm";  ///< --units: length unit stated in STEP/IGES

  bool obj_freeform = false;     ///< --obj-freeform: .obj as the exact free-form surface
  std::string normals = "auto";  ///< --normals: auto, flip, uv (meshes)
};

using io::extension_of;
/// Extensions that -o accepts in this build.
std::vector<std::string> output_extensions();
/// Throws Error(kUsage, option "-o") if no writer handles the extension of `path`.
void check_output_extension(const std::string& path);
/// Throws Error(kUsage, option "--units") unless STEP/IGES can state `units`.
void check_units(const std::string& units);
/// Throws Error(kUsage) for a --mesh-density or --normals no mesh writer accepts.
void check_mesh_options(int mesh_density, const std::string& normals);
/// Writes `path` in the format of its extension (atomically); returns what was written in a
/// few words ("triangle mesh, 64 x 248 samples, ...") for the "wrote" line.
std::string write_output(const std::string& path, const OutputContext& context);

}  // namespace sfit::cli
