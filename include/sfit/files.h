// Files by extension: the reader of every input format and the writer of every output format
// of the format registry (sfit/io/formats.h) this build has, for the CLI and the Python module
// alike. Nothing here prints: the callers say what they want to say.
#pragma once

#include <string>
#include <vector>

#include "sfit/io/file_names.h"
#include "sfit/io/formats.h"
#include "sfit/rows.h"
#include "sfit/surface.h"
#include "sfit/surface_fit.h"

namespace sfit::files {

/// Rows read from a file of any input format.
struct Input {
  Rows rows;
  std::vector<long> first_line;  ///< line of each row's first point, where the format has lines
  std::string name;
  std::vector<bool> closed_rows;  ///< STEP/IGES: the row is a closed curve (empty otherwise)
  std::string units;              ///< STEP/IGES: the file's length unit (mm, m, in, ...)
};
/// Reads input rows by extension (.rows, .srows, .csv, and where this build has the CAD part
/// the section curves of .step/.iges); "-" and unknown extensions read .rows text ("-" from
/// standard input). Throws Error (kUsage for a format this build lacks; the readers' codes).
Input read_input(const std::string& path);

/// What a writer may use: the surface always; the fit and the data when the caller fitted.
struct OutputContext {
  const Surface& surface;
  const FitResult* fit = nullptr;
  const Rows* rows = nullptr;
  std::string input_name;
  bool mesh = false;         ///< --mesh: OBJ as a tessellated mesh (the default anyway)
  int mesh_density = 0;      ///< --mesh-density: samples per direction (0: automatic)
  bool fields = false;       ///< --fields: deviation/curvature point data (VTK)
  std::string units = "mm";  ///< --units: length unit stated in STEP/IGES

  bool obj_freeform = false;     ///< --obj-freeform: .obj as the exact free-form surface
  std::string normals = "auto";  ///< --normals: auto, flip, uv (meshes)
};

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
/// Writes `path` in the format of its extension (atomically); `text` set: the surface JSON
/// into *text instead (for standard output). Returns what was written in a few words
/// ("triangle mesh, 64 x 248 samples, ..."; empty for JSON) for the "wrote" line.
std::string write_output(const std::string& path, const OutputContext& context,
                         std::string* text = nullptr);

}  // namespace sfit::files
