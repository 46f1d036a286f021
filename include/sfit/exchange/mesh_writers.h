// Writers that need no CAD kernel: OBJ (free-form B-spline or mesh), binary STL, PLY, and
// VTK for ParaView. Every file goes through io::write_file_atomically().
#pragma once

#include <string>

#include "sfit/exchange/tessellate.h"
#include "sfit/surface.h"
#include "sfit/surface_fit.h"

namespace sfit::exchange {

/// The exact surface as Wavefront OBJ free-form geometry: `v` lines for the control points
/// in SURFACE_JSON's full storage (u fastest), `cstype bspline`, `deg p q`,
/// `surf u0 u1 v0 v1` with the control-vertex references, `parm u`/`parm v` with the full
/// knot vectors, `end`. In a periodic direction the wrap-around references repeat the indices
/// of the first control points, so the closure is exact and explicit.
void write_obj_freeform(const std::string& path, const Surface& surface);

/// The mesh as OBJ: `v`, `vn`, and `f a//a b//b c//c` triangles.
void write_obj_mesh(const std::string& path, const Mesh& mesh);

/// Binary STL: 80-byte header, triangle count, facet normal and 3 vertices per triangle
/// (float32, little endian).
void write_stl(const std::string& path, const Mesh& mesh);

/// Binary little-endian PLY: vertex x y z (double) nx ny nz (float), face vertex_indices
/// (uchar count, int indices).
void write_ply(const std::string& path, const Mesh& mesh);

/// Point data for the VTK writers. With a fit, the data points are added too (see below).
struct VtkFields {
  bool curvature = false;          ///< mean_curvature, gaussian_curvature on the grid
  const FitResult* fit = nullptr;  ///< with rows: the data points and their deviation
  const Rows* rows = nullptr;
};

/// Legacy VTK (binary: ASCII VTK cannot carry NaN) POLYDATA: the sampled grid as quads (POLYGONS),
/// normals as point data; with fields.curvature, mean and Gaussian curvature; with a fit and its
/// rows, the data points as VERTICES with point data "deviation" (S(u,v) - D, a vector) and
/// "deviation_ratio" (max over axes |S - D| / T), NaN on the grid points, where those are not
/// defined, and the grid points' curvature evaluated at each data point's (u, v).
void write_vtk(const std::string& path, const Surface& surface, const Mesh& mesh,
               const VtkFields& fields);

/// VTK XML StructuredGrid (.vts, inline base64 binary): the sample grid with its normals, and with
/// fields.curvature its mean and Gaussian curvature. A structured grid holds no scattered
/// points: the deviation at the data points is in the .vtk writer only. A periodic direction
/// repeats its first sample at the end so the grid closes in ParaView.
void write_vts(const std::string& path, const Surface& surface, const Mesh& mesh,
               const VtkFields& fields);

}  // namespace sfit::exchange
