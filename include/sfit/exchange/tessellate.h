// Triangle meshes sampled from the surface, with the density chosen from a chordal error bound.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sfit/surface.h"

namespace sfit::exchange {

/// A regular grid of samples S(u_a, v_b) and its triangles. Vertex (a, b) is
/// vertices[b * samples_u + a]: u varies fastest. A periodic direction does not repeat its
/// first sample column/row; the triangles wrap around instead, so a closed direction is one
/// watertight band with no seam.
struct Mesh {
  int samples_u = 0, samples_v = 0;
  bool periodic_u = false, periodic_v = false;
  std::vector<double> u, v;                             ///< the sample parameters
  std::vector<Point> vertices;                          ///< samples_u * samples_v points
  std::vector<Point> normals;                           ///< unit normals (see `flipped`)
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise about the normal
  /// false: normals along S_u x S_v, triangles (a,b) (a+1,b) (a+1,b+1); true: orient() turned
  /// both, normals along -(S_u x S_v) and each triangle's last two corners swapped.
  bool flipped = false;
  std::string orientation = "as the data runs (S_u x S_v)";  ///< what orient() chose, for humans
  double chordal_bound = -1;  ///< make_mesh(): the density's chordal error bound (-1: given)

  int quads_u() const { return periodic_u ? samples_u : samples_u - 1; }
  int quads_v() const { return periodic_v ? samples_v : samples_v - 1; }
  std::uint32_t index(int a, int b) const {
    return static_cast<std::uint32_t>((b % samples_v) * samples_u + (a % samples_u));
  }
};

/// Samples per direction for a mesh whose chordal error stays below `chord`.
///
/// METHOD: the distance from S to the triangle over a parameter cell of size h_u x h_v is at
/// most (h_u^2 M_uu + 2 h_u h_v M_uv + h_v^2 M_vv) / 8 (linear interpolation error along the
/// longest edge, de Boor, "A Practical Guide to Splines", ch. 2), with M the maxima of
/// |S_uu|, |S_uv|, |S_vv| sampled 4 times per knot span. h_u and h_v are chosen so that
/// h_u^2 M_uu = h_v^2 M_vv and the bound equals `chord`. At least 4 samples per knot span
/// (so the shape of every span shows); at most `max_samples` per direction.
struct Density {
  int samples_u = 0, samples_v = 0;
  double bound = 0;  ///< the chordal error bound these counts give (<= chord unless capped)
};
/// With `max_triangles` > 0, the spacing grows by one factor in both directions until the
/// mesh has at most that many triangles (but never fewer than one cell per knot span); `bound`
/// then says what the coarser mesh holds. Computed in coordinates scaled by the surface's size,
/// so any accepted extent (1e-150 ... 1e150) and offset gives the same counts.
Density choose_density(const Surface& surface, double chord, int max_samples = 4096,
                       double max_triangles = 0);

/// The default chordal error: tolerance / 4, or 2.5e-4 of the control net's bounding-box
/// diagonal when there is no tolerance (convert, T = 0).
double default_chord(const Surface& surface, double tolerance);

/// Triangles a default mesh holds at most (about 5 MB of binary STL): the chordal target
/// above is kept where it fits, the mesh is coarsened evenly where it does not.
inline constexpr double kDefaultTriangleBudget = 100000;

/// Samples the surface on a samples_u x samples_v grid, uniform in each parameter, and
/// triangulates it (two triangles per cell). samples 2 ... 100000 in an open direction,
/// 3 ... 100000 in a periodic one, at most 5e7 in all; throws Error(kUsage, option
/// "--mesh-density") otherwise.
/// Vertices are Surface::evaluate() at the samples. Normals: S_u x S_v normalised, computed in
/// coordinates scaled by the surface's size (no overflow or underflow at any accepted
/// extent); where it vanishes (a pole, where a row of one point collapsed an edge) the limit
/// normal: the normal just beside the point (1e-4 of a knot span inward), averaged over a
/// whole collapsed row or column so the pole has one normal.
Mesh tessellate(const Surface& surface, int samples_u, int samples_v);

/// How normals (and the triangles' winding with them) are oriented: kAuto outward for a
/// surface closed in u or v (the sign of the volume it encloses, its open ends capped flat),
/// up (+z) for a height field (open in both directions, every normal's z of one sign), and
/// as the data runs (S_u x S_v) otherwise; kFlip the opposite of kAuto; kData S_u x S_v.
enum class NormalRule { kAuto, kFlip, kData };
/// "auto", "flip", "uv" (the CLI's --normals); throws Error(kUsage, option "--normals").
NormalRule parse_normal_rule(const std::string& name);
/// Orients `mesh` (from tessellate(), normals along S_u x S_v) by `rule`; sets `flipped` and
/// `orientation` ("outward (closed in u)", "up (+z)", ...).
void orient(Mesh& mesh, NormalRule rule);

/// The mesh the writers use: `samples` per direction (0: choose_density() at
/// default_chord(tolerance) within kDefaultTriangleBudget), oriented by `rule`.
Mesh make_mesh(const Surface& surface, int samples, double tolerance, NormalRule rule);

/// Principal-curvature summaries at (u, v): mean H (about the S_u x S_v normal) and Gaussian
/// K, from the first and second fundamental forms in coordinates scaled by the surface's
/// size (H and K are then scaled back, so any accepted extent gives finite values). At a
/// degenerate point (S_u x S_v vanishes: a pole) the value just beside it, 1e-4 of a knot
/// span inward (`limit` true); NaN only where that is degenerate too.
struct Curvature {
  double mean = 0, gaussian = 0;
  bool limit = false;
};
Curvature curvature(const Surface& surface, double u, double v);

}  // namespace sfit::exchange
