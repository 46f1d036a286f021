// Writers that need no CAD kernel: OBJ (free-form B-spline or mesh), binary STL, PLY, and
// VTK for ParaView. Every file goes through io::write_file_atomically().
#pragma once

#include <string>

#include "sfit/exchange/tessellate.h"
#include "sfit/surface.h"
#include "sfit/surface_fit.h"

namespace sfit::exchange {

/// The exact surface as Wavefront OBJ free-form geometry: `v` lines for the control points
/// in the full storage of docs/surface-json.md (u fastest), `cstype bspline`, `deg p q`,
/// `surf u0 u1 v0 v1` with the control-vertex references, `parm u`/`parm v` with the full
/// knot vectors, `end`. In a periodic direction the wrap-around references repeat the indices
/// of the first control points, so the closure is exact and explicit.
void write_obj_freeform(const std::string& path, const Surface& surface);

/// The mesh as OBJ: `v`, `vn`, and `f a//a b//b c//c` triangles.
void write_obj_mesh(const std::string& path, const Mesh& mesh);

/// Binary STL: 80-byte header, triangle count, facet normal and 3 vertices per triangle
/// (float32, little endian). Refused (check_stl_fits) where float32 cannot hold the vertices.
void write_stl(const std::string& path, const Mesh& mesh);

/// Largest rounding of a vertex to float32, relative to the mesh's size (bounding-box
/// diagonal), that STL accepts: a far offset (1e7 with a size of 1) fails.
inline constexpr double kStlRounding = 1e-4;
/// Throws Error(kOutputWrite, file `path`) when float32 cannot hold the mesh: coordinates
/// beyond 3.4e38, a size float32 does not resolve (below 1e-6 of the largest coordinate or
/// 1e-30), or rounding that moves a vertex by more than kStlRounding of the size; the message
/// names the double-precision formats to use instead.
void check_stl_fits(const std::string& path, const Mesh& mesh);

/// Binary little-endian PLY: vertex x y z (double) nx ny nz (float), face vertex_indices
/// (uchar count, int indices).
void write_ply(const std::string& path, const Mesh& mesh);

/// Point data for the VTK writers. With a fit, the data points are added too (see below).
struct VtkFields {
  bool curvature = false;          ///< mean_curvature, gaussian_curvature on the grid
  const FitResult* fit = nullptr;  ///< with rows: the data points and their deviation
  const Rows* rows = nullptr;
};

/// Legacy VTK (binary: ASCII VTK cannot carry NaN) POLYDATA: the sampled grid as quads
/// (POLYGONS, wound with the mesh's normals), normals as point data; with a fit and its rows,
/// the data points as VERTICES after the grid points. Point data:
/// - normals: the mesh's (oriented) unit normals; at the data points the normal there.
/// - with fields.curvature: mean_curvature (about those normals), gaussian_curvature, and
///   mean_curvature_clipped / gaussian_curvature_clipped, clamped to the 1st ... 99th
///   percentile of the grid values, which field data mean_curvature_range /
///   gaussian_curvature_range (2 values) give: colour by the clipped field.
/// - with a fit: deviation (S(u,v) - D, a vector) and deviation_ratio (max over axes
///   |S - D| / T), exact at the data points, interpolated from them on the grid.
/// No NaN but at a genuinely degenerate point (where even the limit is undefined).
void write_vtk(const std::string& path, const Surface& surface, const Mesh& mesh,
               const VtkFields& fields);

/// VTK XML StructuredGrid (.vts, inline base64 binary): the sample grid with the point data
/// of write_vtk() on the grid (the deviation interpolated from the data points) and the same
/// field data. A periodic direction repeats its first sample at the end so the grid closes
/// in ParaView; a flipped mesh runs i backwards so the cells wind with the normals.
void write_vts(const std::string& path, const Surface& surface, const Mesh& mesh,
               const VtkFields& fields);

}  // namespace sfit::exchange
