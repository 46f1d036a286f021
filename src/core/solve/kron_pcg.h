// Conjugate gradients on the tensor-product normal equations of ragged rows, preconditioned
// by their nearest Kronecker product (docs/control-points.md). Private to tensor_lsq.cpp.
//
// PURPOSE  Solve A x = b, A = sum_j (b_v(v_j) b_v(v_j)^T) (x) G_j (tensor_lsq.h), faster than
//          a sparse Cholesky factorisation of A where the rows' Gram matrices G_j are alike.
// METHOD   With s_j = trace(G_j) and Gbar = sum_j G_j / sum_j s_j, the matrix
//          P = Gbar (x) H_s, H_s = sum_j s_j b_v(v_j) b_v(v_j)^T, equals A when every G_j is
//          s_j Gbar (rows sharing their u: a grid at the uniform rule) and is close to it where
//          the rows' parameters are alike (a grid at the chord or centripetal rule, rows of
//          similar point distributions). P^-1 r costs two banded solves per axis
//          (Z = H_s^-1 R Gbar^-1 with R the residual as an nv x nu matrix), so each iteration
//          costs about as much as one product with A, and Eigen's ConjugateGradient with
//          this preconditioner converges in tens of iterations.
// WHY      The Cholesky factor of A fills the band: nu nv (min(nu, nv) degree)^2 flops per
//          pair, 55 % of a volcano fit at 1e-3 before this. bench_fit's
//          BM_TensorSolveRagged (chord rule, ragged rows, one thread, CPU): 10^4 points at
//          20 x 20 0.45 ms against 1.17 ms factorised, at 40 x 40 3.2 against 8.7 ms; 10^5
//          points at 60 x 60 5.2 against 32 ms. Where CG does not reach its tolerance in
//          kMaxIterations the caller falls
//          back to the factorisation; every surface is checked at every point either way, so
//          an inexact solve costs optimality at most, never the tolerance.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace sfit::detail {

/// A x = rhs for A (upper triangle stored, unknown (i, l) numbered i * nv + l) by CG with the
/// preconditioner Gbar (x) H_s (both nu x nu and nv x nv, upper triangles). False where a
/// factor is singular or CG did not converge (x is then unspecified). `iterations` (optional)
/// receives the most iterations any axis took. Deterministic: the same bits for any threads.
bool solve_kron_pcg(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixX3d& rhs,
                    const Eigen::SparseMatrix<double>& Gbar, const Eigen::SparseMatrix<double>& Hs,
                    Eigen::MatrixX3d& x, int* iterations = nullptr);

}  // namespace sfit::detail
