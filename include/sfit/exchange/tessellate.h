// Triangle meshes sampled from the surface, with the density chosen from a chordal error bound.
#pragma once

#include <array>
#include <cstdint>
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
  std::vector<Point> normals;                           ///< unit normals, S_u x S_v direction
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise about the normal

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
/// |S_uu|, |S_uv|, |S_vv| sampled 8 times per knot span. h_u and h_v are chosen so that
/// h_u^2 M_uu = h_v^2 M_vv and the bound equals `chord`. At least 4 samples per knot span
/// (so the shape of every span shows); at most `max_samples` per direction.
struct Density {
  int samples_u = 0, samples_v = 0;
  double bound = 0;  ///< the chordal error bound these counts give (<= chord unless capped)
};
Density choose_density(const Surface& surface, double chord, int max_samples = 4096);

/// The default chordal error: tolerance / 4, or 2.5e-4 of the control net's bounding-box
/// diagonal when there is no tolerance (convert, T = 0).
double default_chord(const Surface& surface, double tolerance);

/// Samples the surface on a samples_u x samples_v grid, uniform in each parameter, and
/// triangulates it (two triangles per cell). samples >= 2 in an open direction, >= 3 in a
/// periodic one; throws Error(kUsage, option "--mesh-density") otherwise.
/// Normals: S_u x S_v normalised; where that vanishes (a pole, where a row of one point
/// collapsed an edge) the area-weighted mean of the normals of the triangles around it.
Mesh tessellate(const Surface& surface, int samples_u, int samples_v);

/// Principal-curvature summaries at (u, v): mean H and Gaussian K (first and second
/// fundamental forms from Surface::derivatives(); NaN where S_u x S_v vanishes).
struct Curvature {
  double mean = 0, gaussian = 0;
};
Curvature curvature(const Surface& surface, double u, double v);

}  // namespace sfit::exchange
