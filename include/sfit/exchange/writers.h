// Every output format besides the JSON contract, chosen by the file extension (the CLI's -o).
#pragma once

#include <string>
#include <vector>

#include "sfit/rows.h"
#include "sfit/surface.h"
#include "sfit/surface_fit.h"

namespace sfit::exchange {

struct WriteOptions {
  bool mesh = false;         ///< .obj: a tessellated mesh instead of free-form geometry
  int mesh_density = 0;      ///< samples per direction; 0: from the chordal error bound
  bool fields = false;       ///< .vtk/.vts: curvature (and with a fit, the deviation)
  double tolerance = 0;      ///< the fit's tolerance (smallest axis); 0: none known
  std::string units = "mm";  ///< .step/.igs: the stated length unit
};

/// Extensions handled here, lower case without the dot: step, stp, igs, iges, obj, stl, ply,
/// vtk, vts.
std::vector<std::string> writer_extensions();

/// The densities --mesh-density accepts whatever the surface: 0 (automatic) or
/// kMinMeshDensity ... kMaxMeshDensity samples per direction (the mesh stays below 5e7
/// vertices, and its time to seconds). Throws Error(kUsage, option "--mesh-density") otherwise, before any work.
inline constexpr int kMinMeshDensity = 3;
inline constexpr int kMaxMeshDensity = 4096;
void check_mesh_density(int samples);

/// Writes `surface` to `path` in the format of its extension, atomically.
/// `fit` and `rows` (either may be null) add the deviation fields to .vtk.
/// Throws Error(kUsage) for an unknown extension, a bad density or unit, and
/// Error(kOutputWrite) when the file cannot be written.
void write_surface(const std::string& path, const Surface& surface, const WriteOptions& options,
                   const FitResult* fit, const Rows* rows);

}  // namespace sfit::exchange
