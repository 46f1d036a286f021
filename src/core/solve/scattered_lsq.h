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

#include <cstddef>
#include <span>
#include <vector>

#include "sfit/rows.h"
#include "sfit/surface.h"

namespace sfit::detail {

/// The largest store a search keeps per thread from one pair's solve to the next (a larger one
/// is given back after its solve). Up to three such stores per thread (the band, the factor, the
/// geometric search's data term) stay with a thread for its life: up to about 100 MB a pool
/// thread in a long-lived process (Python, the editor's server).
inline constexpr std::size_t kKeptStoreBytes = std::size_t{32} << 20;

/// The smoothness weight relative to the mean diagonal of the data term.
inline constexpr double kSmoothing = 1e-4;

/// A control point whose data term (its diagonal) is below this fraction of the mean diagonal
/// is weakly held by the data: the calm term (solve()'s `calm`) ties it to its neighbours.
inline constexpr double kWeaklyHeld = 0.05;

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
/// The data term as scattered_add() with each point's basis given instead of evaluated on
/// uniform knots (any knots): per point the first control point along u (v) and degree_u + 1
/// (degree_v + 1) values, as DirectionBasis at order 0 (sfit/surface_eval.h). `pts` empty:
/// the band only.
void scattered_add_basis(const ScatteredSpec& spec, int nu, int nv, std::span<const Point> pts,
                         std::span<const int> first_u, std::span<const double> bu,
                         std::span<const int> first_v, std::span<const double> bv,
                         std::vector<double>& band, std::vector<Point>& rhs);
/// The surface of a summed data term (scattered_add()) plus the smoothness term of weight
/// `smoothing` (relative), as ScatteredProblem::solve().
bool scattered_solve(const ScatteredSpec& spec, int nu, int nv, const std::vector<double>& band,
                     const std::vector<Point>& rhs, double smoothing, Surface& out, double calm = 0,
                     const Point* normal = nullptr);

/// scattered_solve()'s system (the summed data term plus the smoothness term) factorised once,
/// then solved for any number of right-hand sides: the banded Cholesky factor in the ordering
/// of the narrower band (v-major where u is closed, u-major where v is closed; not both).
class ScatteredFactor {
 public:
  /// false where the system is singular (a pivot at round-off), the band store does not match
  /// (nu, nv) or both directions are closed.
  /// `calm` > 0: with the calm term of ScatteredProblem::solve() on every axis.
  /// `plain` (with `calm` > 0): also factorises the system without the calm term into it, from
  /// the same assembly (the data and smoothness terms are added once; the same bits as its own
  /// factor() without `calm`); false where either factorisation fails.
  bool factor(const ScatteredSpec& spec, int nu, int nv, const std::vector<double>& band,
              double smoothing, double calm = 0, ScatteredFactor* plain = nullptr);
  /// x <- A^-1 x in place, x[I] for unknown I = i nv + l (the Surface's order).
  void solve(std::vector<Point>& x) const;
  void solve(std::vector<double>& x) const;
  /// The bytes its factor holds (kept for the next factorisation's use).
  std::size_t bytes() const { return L_.capacity() * sizeof(double); }

 private:
  template <class T>
  void solve_in_place(std::vector<T>& x) const;
  long pos(std::size_t I) const;
  int nu_ = 0, nv_ = 0;
  bool v_major_ = false;
  long b_ = 0;
  std::vector<double> L_;  // L(r, c), c <= r, at L_[r (b_ + 1) + c - r + b_]
};

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
  /// `calm` > 0 (relative, as `smoothing`) adds the calm term: the squared first differences
  /// between neighbouring control points (along u and along v) where either is weakly held by
  /// the data (kWeaklyHeld), so that the net is flat, not continued linearly, across the parts
  /// of the domain without data: a steep edge at the data's border (a roof, a tree) is not
  /// extrapolated across an empty corner. 0 (the search): the same bits as without it.
  /// `normal` (unit): the calm term acts on the control points' component along it only (a
  /// sheet's height over its base plane; the net stays continued linearly in the plane, so
  /// it does not fold there), at the cost of a second factorisation.
  bool solve(int nu, int nv, double smoothing, Surface& out, double calm = 0,
             const Point* normal = nullptr) const;
  /// solve()'s data term at (nu, nv) (scattered_add() over all points), for scattered_solve()
  /// at several smoothness weights without summing it again. Counts at least min_u(), min_v().
  /// `extra` (one per point, or empty): each point's weight multiplied by it (the reweighted
  /// fit of geometric_reweight.h); empty gives the same bits as before.
  void assemble(int nu, int nv, std::vector<double>& band, std::vector<Point>& rhs,
                std::span<const double> extra = {}) const;
  /// The flops of solve()'s factorisation at (nu, nv): unknowns x band^2 / 2.
  double cost(int nu, int nv) const;

 private:
  const Rows& rows_;
  ScatteredSpec spec_;
  std::vector<double> fu_, fv_;
};

}  // namespace sfit::detail
