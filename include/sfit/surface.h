// The tensor-product B-spline surface sfit produces (docs/method.md section 2).
#pragma once

#include <vector>

#include "sfit/knot_vector.h"
#include "sfit/rows.h"

namespace sfit {

/// S(u,v) = sum_i sum_j B_i,degree_u(u) B_j,degree_v(v) P_ij, u along the rows, v across
/// them, on the knots `knots_u`, `knots_v`: uniform by default (knot_vector.h), or any valid
/// KnotVector of the same degree, count and periodic flag (set_knots_u() checks that). `control`
/// holds the distinct control points, row-major in i: P_ij = control[i * count_v + j]. A periodic
/// direction stores its `count` distinct points; full_knots_u() and full_control() give the
/// docs/surface-json.md form with the wrap copies.
struct Surface {
  int degree_u = 3;
  int degree_v = 3;
  bool periodic_u = false;
  bool periodic_v = false;
  int count_u = 0;  ///< distinct control points along u (nu)
  int count_v = 0;  ///< distinct control points along v (nv)
  std::vector<Point> control;
  KnotVector knots_u;  ///< uniform unless set: the knots along u
  KnotVector knots_v;

  /// Sets non-uniform (or uniform) knots; Error kUsage unless `k` matches the direction's
  /// degree, count and periodic flag (a default KnotVector, uniform, always matches).
  void set_knots_u(KnotVector k);
  void set_knots_v(KnotVector k);
  /// True if either direction has non-uniform knots.
  bool non_uniform() const { return !knots_u.uniform() || !knots_v.uniform(); }

  const Point& at(int i, int j) const { return control[static_cast<std::size_t>(i) * count_v + j]; }
  Point& at(int i, int j) { return control[static_cast<std::size_t>(i) * count_v + j]; }

  /// Parameter domain [0, u_end()] x [0, v_end()].
  double u_end() const;
  double v_end() const;
  /// S(u,v); parameters are clamped into, or wrapped around, the domain.
  Point evaluate(double u, double v) const;
  /// Partial derivatives at (u,v): out[0] = S, out[1] = S_u, out[2] = S_v, out[3] = S_uu,
  /// out[4] = S_uv, out[5] = S_vv.
  void derivatives(double u, double v, Point out[6]) const;

  /// Stored control-point counts: count + degree for a periodic direction.
  int full_count_u() const { return count_u + (periodic_u ? degree_u : 0); }
  int full_count_v() const { return count_v + (periodic_v ? degree_v : 0); }
  /// Full knot vectors, length full_count + degree + 1 (docs/surface-json.md).
  std::vector<double> full_knots_u() const;
  std::vector<double> full_knots_v() const;
  /// Control point (i, j) of the full arrays, 0 <= i < full_count_u().
  const Point& full_at(int i, int j) const { return at(i % count_u, j % count_v); }
};

}  // namespace sfit
