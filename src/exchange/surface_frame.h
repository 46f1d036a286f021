// The surface in coordinates scaled by its own size, so that products of derivatives
// (normals, fundamental forms, densities) neither overflow nor underflow at any accepted
// extent (1e-150 ... 1e150) or offset. Private to the mesh code.
#pragma once

#include "sfit/exchange/tessellate.h"
#include "sfit/surface.h"

namespace sfit::exchange::detail {

struct SurfaceFrame {
  Surface scaled;  ///< control points (P - centre) / size: every coordinate within [-1, 1]
  Point centre = Point::Zero();
  double size = 1;  ///< a power of two >= max |P - centre| per axis (1 for a single point)

  explicit SurfaceFrame(const Surface& s);
  /// Derivatives of the scaled surface (out[0] = (S - centre) / size, as Surface::derivatives).
  void derivatives(double u, double v, Point out[6]) const { scaled.derivatives(u, v, out); }
  /// Unit S_u x S_v at scaled derivatives d; false where it is degenerate (|S_u| or |S_v|
  /// below 1e-10 of the size, or the sine of their angle below 1e-8).
  static bool unit_normal(const Point d[6], Point& n);
  /// The normal at (u, v), or beside a degenerate point (1e-4 of a knot span inward along the
  /// collapsed direction, then the other, then both); false if all of those are degenerate.
  bool normal_near(double u, double v, Point& n) const;
  /// Curvature of the original surface at (u, v) (see exchange::curvature()).
  Curvature curvature(double u, double v) const;
};

}  // namespace sfit::exchange::detail
