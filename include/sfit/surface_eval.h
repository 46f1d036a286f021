// Evaluation of a Surface beyond its points: partial derivatives from one pass over the basis,
// the same on a grid (each direction's basis evaluated once), curvature, and the closest point
// of the surface to a point in space.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "sfit/surface.h"

namespace sfit {

/// How many points surface_derivatives() writes for `order` 0, 1, 2: 1, 3, 6.
inline constexpr int derivative_count(int order) {
  return order <= 0 ? 1 : order == 1 ? 3 : 6;
}

/// S and its partial derivatives up to `order` (0, 1 or 2) at (u, v), from one evaluation of
/// the basis functions and their derivatives in each direction: out[0] = S, out[1] = S_u,
/// out[2] = S_v and, for order 2, out[3] = S_uu, out[4] = S_uv, out[5] = S_vv (the layout of
/// Surface::derivatives()). out[0] equals Surface::evaluate(u, v) bit for bit. Parameters are
/// clamped or wrapped as in evaluate(). Throws Error(kUsage) for an order outside 0 ... 2.
void surface_derivatives(const Surface& s, double u, double v, int order, Point* out);

/// One partial derivative d^(du+dv) S / du^du dv^dv (du, dv >= 0, du + dv <= 2) at (u, v):
/// the basis of each direction only to the order it needs and one sum over the control
/// points, so S_u costs about what S does. Equals surface_derivatives()'s slot up to
/// round-off (the same sums in the same order: bit for bit). Throws Error(kUsage) otherwise.
Point surface_partial(const Surface& s, double u, double v, int du, int dv);

/// The basis of one direction at a list of parameters, evaluated once for a grid.
struct DirectionBasis {
  int degree = 0;
  int order = 0;
  std::vector<int> first;  ///< per parameter: the control point the first value multiplies
  std::vector<double> d;   ///< per parameter (order + 1) x (degree + 1) values, derivative-major
};

/// The basis along u (`along_u`) or v of `s` at `t`, derivatives up to `order`.
DirectionBasis direction_basis(const Surface& s, bool along_u, std::span<const double> t,
                               int order);

/// surface_derivatives() at (u_i, v_j) from the bases of both directions (same order): the
/// same bits as surface_derivatives(s, u_i, v_j, order, out).
void surface_derivatives(const Surface& s, const DirectionBasis& u, std::size_t i,
                         const DirectionBasis& v, std::size_t j, Point* out);

/// surface_partial() from the bases of both directions (u.order >= du, v.order >= dv).
Point surface_partial(const Surface& s, const DirectionBasis& u, std::size_t i,
                      const DirectionBasis& v, std::size_t j, int du, int dv);

/// Curvature at a point with respect to the unit normal n = S_u x S_v / |S_u x S_v| (the
/// orientation of Surface's normal): a surface that bends away from n has negative normal
/// curvature, so a sphere whose normal points outward has mean -1/R and Gaussian 1/R^2.
/// k1 >= k2 are the principal curvatures, gaussian = k1 k2, mean = (k1 + k2) / 2. Where
/// S_u x S_v vanishes (a pole, a degenerate edge) every value is NaN.
struct Curvature {
  double gaussian = 0;
  double mean = 0;
  double k1 = 0;
  double k2 = 0;
};

/// The curvature from S, S_u, S_v, S_uu, S_uv, S_vv (surface_derivatives()'s order 2).
Curvature curvature_from(const Point d[6]);
Curvature surface_curvature(const Surface& s, double u, double v);

/// The point of a surface nearest to a point in space.
struct ClosestPoint {
  double u = 0;  ///< in [0, u_end] (open) or [0, u_end) (periodic)
  double v = 0;
  Point point = Point::Zero();  ///< S(u, v)
  double distance = 0;          ///< |S(u, v) - p|
};

/// Finds closest points on one surface: the surface is sampled once on a grid (about four
/// samples per knot span, between 8 and 256 per direction); each query starts from its
/// nearest sample and descends with Newton's method on |S(u, v) - p|^2, with a line search
/// that never increases the distance, and projected onto the domain in an open direction
/// (an edge or a corner is reached exactly when the nearest point lies on it).
class ClosestPointFinder {
 public:
  explicit ClosestPointFinder(const Surface& surface);
  ClosestPoint find(const Point& p) const;

 private:
  const Surface& surface_;
  std::vector<double> su_, sv_;  // sample parameters
  std::vector<Point> samples_;   // S(su_[a], sv_[b]) at a * sv_.size() + b
};

}  // namespace sfit
