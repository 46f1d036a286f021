// Tensor-product least squares over scattered parameters: every data point has its own (u, v)
// (Parametrization::kGeometric, docs/method.md 7.9), at a pair of counts (nu, nv) on uniform
// knots, with a small smoothness term on the control net. Private to the surface search.
//
// PURPOSE  min sum_k w_k |S(u_k, v_k) - D_k|^2 + lambda (|D_u P|^2 + |D_v P|^2) over the nu x nv
//          control points P, D_u and D_v the second differences of the control net along u
//          and v (wrapped in a closed direction).
// METHOD   Normal equations: each point adds the (p+1)(q+1) x (p+1)(q+1) products of its
//          basis values into a band store ((2p+1)(2q+1) neighbours per control point), in
//          fixed blocks of points per thread (the same sums for any thread count); then the
//          matrix plus lambda (D_u^T D_u + D_v^T D_v) in the ordering of the narrower band
//          (u-major, band p nv + q, or v-major, band q nu + p; v-major where u is closed, so
//          the wrap stays within (q + 1) nu), factorised by a banded Cholesky, three right-hand
//          sides. A general sparse LDL^T (Eigen's simplicial, AMD) was 10x slower at the sizes
//          the search tries (a few hundred to 10^4 unknowns).
// WHY      Rows clipped by a boundary, holes and ragged sections leave knot spans without
//          data: plain least squares is singular there. The smoothness term decides what data
//          does not: the net continues linearly (second differences vanish) across an empty
//          span, so the surface stays calm, and the system stays positive definite. Where
//          data is, lambda (a small fraction of the data term's mean diagonal) only slightly
//          pulls the fit; the caller checks every point and lowers lambda where T was missed.
#pragma once

#include <span>
#include <vector>

#include "sfit/rows.h"
#include "sfit/surface.h"

namespace sfit::detail {

/// The smoothness weight relative to the mean diagonal of the data term.
inline constexpr double kSmoothing = 1e-4;

struct ScatteredSpec {
  int degree_u = 3, degree_v = 3;
  bool closed_u = false, closed_v = false;
  int threads = 1;
};

/// The data term of points `pts` (centred; weights `wts` or none) at fractions `fu`, `fv` and
/// counts (nu, nv), added into `band` (nu nv x (2p+1)(2q+1), u-major, each control point's
/// neighbours) and `rhs` (nu nv): ScatteredProblem::solve()'s assembly of one block of points
/// (also one chunk of a distributed fit's points: the sums over blocks add up).
void scattered_add(const ScatteredSpec& spec, int nu, int nv, std::span<const Point> pts,
                   std::span<const double> wts, std::span<const double> fu,
                   std::span<const double> fv, std::vector<double>& band, std::vector<Point>& rhs);
/// The surface of a summed data term (scattered_add()) plus the smoothness term of weight
/// `smoothing` (relative), as ScatteredProblem::solve().
bool scattered_solve(const ScatteredSpec& spec, int nu, int nv, const std::vector<double>& band,
                     const std::vector<Point>& rhs, double smoothing, Surface& out);

class ScatteredProblem {
 public:
  /// `rows` (centred coordinates) must outlive the problem; `fu`, `fv`: each point's position
  /// as a fraction of the domain, in [0, 1] ([0, 1) in a closed direction), rows.points() order.
  ScatteredProblem(const Rows& rows, const ScatteredSpec& spec, std::vector<double> fu,
                   std::vector<double> fv);
  const Rows& rows() const { return rows_; }
  const ScatteredSpec& spec() const { return spec_; }
  const std::vector<double>& fractions_u() const { return fu_; }
  const std::vector<double>& fractions_v() const { return fv_; }
  /// The smallest counts of the degrees (a closed direction: 2 degree + 1).
  int min_u() const;
  int min_v() const;
  /// u (v) of every point at nu (nv): the fraction times the domain's end.
  std::vector<double> u_at(int nu) const;
  std::vector<double> v_at(int nv) const;
  /// The surface at (nu, nv) with smoothness weight `smoothing` (relative, see above) into
  /// `out` (centred); false where the factorisation failed or the result is not finite.
  bool solve(int nu, int nv, double smoothing, Surface& out) const;
  /// solve()'s data term at (nu, nv) (scattered_add() over all points), for scattered_solve()
  /// at several smoothness weights without summing it again. Counts at least min_u(), min_v().
  void assemble(int nu, int nv, std::vector<double>& band, std::vector<Point>& rhs) const;
  /// The flops of solve()'s factorisation at (nu, nv): unknowns x band^2 / 2.
  double cost(int nu, int nv) const;

 private:
  const Rows& rows_;
  ScatteredSpec spec_;
  std::vector<double> fu_, fv_;
};

}  // namespace sfit::detail
