// Output formats chosen by the -o extension. The JSON contract is built in; optional parts
// (exchange, render) register theirs in outputs.cpp under their SFIT_HAVE_* switch.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sfit/io/file_names.h"
#include "sfit/io/formats.h"
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
/// Extensions -o accepts in this build (the registry's surface formats this build writes).
std::vector<std::string> output_extensions();
/// Throws Error(kUsage, naming `option`) unless the format registry has a format of `kind`
/// that this build writes for the extension of `path` (unknown, or known but its part is not
/// built: both named).
void check_output_extension(const std::string& path, const std::string& option = "-o",
                            io::FormatKind kind = io::FormatKind::kSurface);
/// Checks the options that shape the surface outputs (--units, --mesh-density, --normals)
/// before any work: throws Error(kUsage) naming the option.
void check_output_options(const std::string& units, int mesh_density,
                          const std::string& normals = "auto");
/// Help text of --mesh-density with the range the mesh part accepts.
std::string mesh_density_help();
/// Writes `path` in the format of its extension (atomically); `text` set: the surface JSON
/// into *text instead (for standard output). Returns what was written in a few words
/// ("triangle mesh, 64 x 248 samples, ..."; empty for JSON) for the "wrote" line.
std::string write_output(const std::string& path, const OutputContext& context,
                         std::string* text = nullptr);

}  // namespace sfit::cli
