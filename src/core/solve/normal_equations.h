// The normal equations of the tensor-product least squares at one pair (nu, nv) (tensor_lsq.h),
// assembled as a sum over rows, and their solve. Private to the core and the Python module's
// distributed fit (python/src/bind_partial.cpp).
//
// PURPOSE  A = sum_j (b_v(v_j) b_v(v_j)^T) (x) G_j and the right-hand sides sum_j b_v(v_j) (x)
//          B_j^T D_j, where row j enters only through its Gram band G_j and moments B_j^T D_j
//          at nu (tensor_lsq.cpp computes them per row; a chunk of a row gives the part of them
//          its points make, and the parts add up).
// METHOD   Everything here is a sum over rows (so over points): A's band in a fixed layout,
//          the right-hand sides, and the Kronecker preconditioner's factors (kron_pcg.h)
//          Gbar s_sum = sum_j G_j, H_s = sum_j s_j b_v b_v^T with s_j = trace(G_j), and s_sum.
//          Two sets of normal equations of disjoint points add to those of their union
//          (add()), so chunks of data spread over machines can be reduced to one set, solved
//          by solve() exactly as TensorProblem::solve() solves the set of all rows at once.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "sfit/surface.h"
#include "tensor_lsq.h"

namespace sfit::detail {

/// A bound on the flops of the sparse factorisation at (nu, nv) (rows not sharing their u).
double full_cost(const TensorSpec& spec, int nu, int nv);
/// The symmetric banded matrix sum over equations of b b^T for a curve (count unknowns,
/// width = degree + 1, cyclic when periodic) from its band G(i, i + d), as a sparse matrix
/// (upper triangle).
Eigen::SparseMatrix<double> band_matrix(const double* G, int count, int width, bool periodic);
/// `out` as the surface of `spec` at (nu, nv), its control points still to be filled.
void shape(Surface& out, const TensorSpec& spec, int nu, int nv);
/// Whether the solve tries conjugate gradients first (kron_pcg.h): spec.iterative, a large
/// enough system, and nu at most a share of the shortest row's points (`min_points`).
bool tries_cg(const TensorSpec& spec, int nu, int nv, int min_points);

/// Whether solve() factorises the system at (nu, nv) as a band (banded_cholesky.h): small
/// enough, and not closed in both directions.
bool solves_as_band(const TensorSpec& spec, int nu, int nv);

struct NormalEquations {
  /// Zero equations at (nu, nv); `kron`: the preconditioner's factors accumulated too.
  NormalEquations(const TensorSpec& spec, int nu, int nv, bool kron);

  /// Adds a row (or part of one) at parameter `v` across the rows: its Gram band G (nu x
  /// (degree_u + 1), G(i, i + d) at G[i * (degree_u + 1) + d]) and moments R (nu points).
  void add_row(const double* G, const Point* R, double v);

  TensorSpec spec;  ///< degrees and closures (its seam offsets are not used here)
  int nu, nv;
  bool kron;
  /// A((i, l), (i + d, l')) at st[((i * nv + l) * wu + d) * sv + (l' - l + degree_v)], d >= 0
  /// (wu = degree_u + 1, sv = 2 degree_v + 1); for d = 0 only l' >= l. Unknown (i, l) is
  /// number i * nv + l, the Surface's order.
  std::vector<double> st;
  Eigen::MatrixX3d rhs;          ///< nu nv x 3
  std::vector<double> gbar, hs;  ///< sum_j G_j (nu x wu), H_s (nv x (degree_v + 1)); kron only
  double s_sum = 0;              ///< sum_j s_j; kron only
};

/// The least-squares surface of the equations into `out` (centred, as the data they were
/// made from); as a band where solves_as_band(), else CG first where `try_cg` (and ne.kron),
/// else the sparse factorisation. false
/// when the system is singular (a span without data) or the solution is not finite.
bool solve(const NormalEquations& ne, bool try_cg, Surface& out);

}  // namespace sfit::detail
