// Tensor-product least squares over all data points at once, at a pair of counts (nu, nv)
// (docs/control-points.md). Private to the surface search.
//
// PURPOSE  min sum_j sum_k |S(u_jk, v_j) - D_jk|^2 over the control points of a uniform
//          tensor-product surface with nu x nv control points, rows of any lengths (ragged).
// METHOD   Normal equations, assembled from per-row moments: row j's data enters only through
//          its Gram matrix G_j = B_j^T B_j (banded, degree_u + 1 wide) and B_j^T D_j (nu
//          numbers per axis), computed once per nu and cached; the surface system is
//          sum_j (b_v(v_j) b_v(v_j)^T) (x) G_j, sparse and symmetric positive definite where
//          every span has data, factorised by CHOLMOD (SuiteSparse, supernodal, with its
//          fill-reducing ordering, which also takes the wrap terms of closed directions).
//          Rows that share their u (a grid at the paper's or uniform rule) share one G, and
//          the problem separates exactly (Kronecker): each row's own fit at nu, then each
//          column of those coefficients fitted across the rows at nv (solve_separable()).
// WHY      The normal equations square the condition number; with uniform knots and data in
//          every span it stays small at the degrees used in practice, and a fit whose solve
//          lost accuracy only loses optimality: every candidate is checked against the
//          original points (check_deviation()) and guarded between them (fit_frame.h).
//          A span without data makes the system singular: that pair does not hold.
//          Weighted rows (Rows::weights(), docs/seams.md) give weighted least squares,
//          min sum w |S - D|^2: their moments are weighted, and no two rows share a Gram matrix.
#pragma once

#include <map>
#include <memory>
#include <vector>

#include "sfit/parametrization.h"
#include "sfit/rows.h"
#include "sfit/surface.h"

namespace sfit::detail {

struct TensorSpec {
  int degree_u = 3, degree_v = 3;
  bool closed_u = false, closed_v = false;
  Parametrization rule = Parametrization::kUniform;  ///< one of the four rules
  int threads = 1;
  /// Closed rows aligned by a fractional seam (docs/seams.md): each row's offset in point
  /// spacings; the geometric rules measure positions from it. Empty: none.
  std::vector<double> seam_offsets;
  /// Rows that do not share their u: conjugate gradients with a Kronecker preconditioner
  /// (kron_pcg.h) before the sparse factorisation; false: the factorisation alone.
  bool iterative = true;
};

class TensorProblem {
 public:
  /// `rows` (centred coordinates) must outlive the problem.
  TensorProblem(const Rows& rows, const TensorSpec& spec);
  /// The same with the positions given (rule != kPaper): per point of `rows` and per row, e.g.
  /// those of a larger data set that `rows` samples (subsample()).
  TensorProblem(const Rows& rows, const TensorSpec& spec, std::vector<double> positions_u,
                std::vector<double> positions_v);
  ~TensorProblem();
  const std::vector<double>& positions_u() const { return positions_u_; }
  const std::vector<double>& positions_v() const { return positions_v_; }

  const TensorSpec& spec() const { return spec_; }
  const Rows& rows() const { return rows_; }
  int min_u() const { return spec_.degree_u + 1; }
  int min_v() const { return spec_.degree_v + 1; }
  /// The largest counts worth trying: the longest row's points, the rows.
  int max_u() const { return max_u_; }
  int max_v() const { return max_v_; }

  /// u of every point (in rows.points() order) at nu; v of every row at nv.
  const std::vector<double>& u_at(int nu);
  std::vector<double> v_at(int nv) const;

  /// The least-squares surface at (nu, nv) into `out` (centred); false when the system is
  /// singular (a span without data) or its solution is not finite.
  bool solve(int nu, int nv, Surface& out);
  /// A bound on the flops of solve() at (nu, nv): unknowns x band width^2 of the natural
  /// ordering (CHOLMOD's ordering does no worse).
  double cost(int nu, int nv) const;

 private:
  struct Moments;
  const Moments& moments(int nu);
  bool solve_separable(int nu, int nv, Surface& out);

  const Rows& rows_;
  TensorSpec spec_;
  int max_u_ = 0, max_v_ = 0;
  int min_points_ = 0;               // the shortest row's points
  bool shared_u_ = false;            // every row has the same u (one Gram for all)
  std::vector<double> positions_u_;  // per point, rule != kPaper
  std::vector<double> positions_v_;  // per row, rule != kPaper
  std::map<int, std::unique_ptr<Moments>> cache_;
  std::size_t cache_bytes_ = 0;
};

/// Every `step`-th point of every row (and each row's last point; their weights too), with the
/// positions of the points kept (from `positions`, per point of `rows`, when not empty) into
/// `sub_positions`.
Rows subsample(const Rows& rows, std::size_t step, const std::vector<double>& positions,
               std::vector<double>& sub_positions);

/// Positions across the rows for the geometric rules, from the data alone: the rows resampled
/// at common fractions of their own positions (their points, where all rows have the same
/// length) form columns; each column's normalized_positions(), averaged over the columns
/// whose points do not all coincide (Piegl and Tiller, The NURBS Book 9.2.5).
std::vector<double> positions_across(const Rows& rows, const std::vector<double>& positions_u,
                                     Parametrization rule, bool closed_u, bool closed_v);

}  // namespace sfit::detail
