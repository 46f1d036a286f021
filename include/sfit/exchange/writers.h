// Every output format besides the JSON contract, chosen by the file extension (the CLI's -o).
#pragma once

#include <string>
#include <vector>

#include "sfit/exchange/tessellate.h"
#include "sfit/options.h"
#include "sfit/rows.h"
#include "sfit/surface.h"
#include "sfit/surface_fit.h"

namespace sfit::exchange {

struct WriteOptions {
  bool mesh = false;          ///< ignored: .obj is a triangle mesh unless obj_freeform
  bool obj_freeform = false;  ///< .obj: the exact free-form B-spline instead of the mesh
  int mesh_density = 0;       ///< samples per direction; 0: from the chordal error bound
  NormalRule normals = NormalRule::kAuto;  ///< meshes: outward / up (see orient())
  bool fields = false;                     ///< .vtk/.vts: curvature (and with a fit, the deviation)
  double tolerance = 0;                    ///< the fit's tolerance (smallest axis); 0: none known
  std::string units = "mm";                ///< .step/.igs: the stated length unit
};

/// Throws Error(kUsage) for a WriteOptions no writer can honour (density out of range, an
/// unknown unit): check before reading any input.
void check_write_options(const WriteOptions& options);

/// Extensions handled here, lower case without the dot: step, stp, igs, iges, obj, stl, ply,
/// vtk, vts.
std::vector<std::string> writer_extensions();

/// The densities --mesh-density accepts whatever the surface: 0 (automatic) or
/// kMinMeshDensity ... kMaxMeshDensity samples per direction (the mesh stays below 5e7
/// vertices, and its time to seconds). Throws Error(kUsage, option "--mesh-density") otherwise,
/// before any work.
// kMinMeshDensity, kMaxMeshDensity: the option table's (sfit/options.h).
void check_mesh_density(int samples);

/// Writes `surface` to `path` in the format of its extension, atomically, and returns what
/// was written in a few words for the user ("triangle mesh, 64 x 248 samples, 31250
/// triangles, chordal error <= 0.002, normals outward (closed in u)"; "free-form B-spline").
/// `fit` and `rows` (either may be null) add the deviation fields to .vtk/.vts.
/// Throws Error(kUsage) for an unknown extension, a bad density or unit, and
/// Error(kOutputWrite) when the file cannot be written (or STL cannot hold the coordinates).
std::string write_surface(const std::string& path, const Surface& surface,
                          const WriteOptions& options, const FitResult* fit, const Rows* rows);

}  // namespace sfit::exchange
