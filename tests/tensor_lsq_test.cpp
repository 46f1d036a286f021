// The surface search's least-squares solver (src/core/solve/tensor_lsq.h, kron_pcg.h): the surface
// at a pair equals a dense least-squares reference on ragged rows, with conjugate gradients
// and with the factorisation alone (as a band where it is small, closed rows or closed
// across too); grids evenly spaced along their rows solve separably at
// the chord rule; weighted rows give weighted least squares; the Kronecker preconditioner is
// exact on a Kronecker system.
#include "tensor_lsq.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <random>

#include "basis.h"
#include "kron_pcg.h"
#include "normal_equations.h"

namespace sfit::detail {
namespace {

Point wavy(double s, double t) {
  return Point(100 * s, 80 * t,
               12 * std::sin(3.1 * s + 0.4) * std::cos(2.3 * t) + 5 * s * t + 2 * std::sin(9 * s));
}

// Ragged rows: row j has 40 ... 79 points at random increasing s (ends included).
Rows ragged_rows(int rows, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> n_of(40, 79);
  std::uniform_real_distribution<double> U(0, 1);
  Rows out;
  for (int j = 0; j < rows; ++j) {
    const int n = n_of(rng);
    std::vector<double> s(n);
    for (double& x : s) x = U(rng);
    std::sort(s.begin(), s.end());
    s.front() = 0;
    s.back() = 1;
    for (double x : s) out.push_point(wavy(x, static_cast<double>(j) / (rows - 1)));
    out.end_row();
  }
  return out;
}

// A ragged tube: closed rows around its axis (`around`), or open rows along it, placed around
// it (closed across the rows); 30 ... 59 points at random angles or positions.
Rows tube_rows(int rows, unsigned seed, bool around) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> n_of(30, 59);
  std::uniform_real_distribution<double> U(0, 1);
  const double two_pi = 2 * std::acos(-1.0);
  Rows out;
  for (int j = 0; j < rows; ++j) {
    std::vector<double> s(n_of(rng));
    for (double& x : s) x = U(rng);
    std::sort(s.begin(), s.end());
    if (!around) {
      s.front() = 0;
      s.back() = 1;
    }
    const double t = static_cast<double>(j) / (around ? rows - 1 : rows);
    for (double x : s) {
      const double phi = two_pi * (around ? x : t), z = 100 * (around ? t : x);
      const double r = 30 + 5 * std::sin(3 * phi + z / 20) + 3 * std::cos(z / 15);
      out.push_point(Point(r * std::cos(phi), r * std::sin(phi), z));
    }
    out.end_row();
  }
  return out;
}

// The (weighted) least-squares control points at (u, v) from the dense design matrix (QR).
Eigen::MatrixX3d dense_reference(const Rows& rows, const std::vector<double>& u,
                                 const std::vector<double>& v, int nu, int nv, int p,
                                 bool closed_u = false, bool closed_v = false) {
  const long N = static_cast<long>(rows.total_points());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(N, static_cast<long>(nu) * nv);
  Eigen::MatrixX3d D(N, 3);
  std::vector<double> bu(p + 1), bv(p + 1);
  long r = 0;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const int fv = eval_basis(p, nv, closed_v, v[j], bv.data());
    for (std::size_t k = 0; k < rows[j].size(); ++k, ++r) {
      const int fu = eval_basis(p, nu, closed_u, u[rows.offsets()[j] + k], bu.data());
      for (int a = 0; a <= p; ++a)
        for (int b = 0; b <= p; ++b)
          A(r, wrap_index(fu + a, nu) * nv + wrap_index(fv + b, nv)) += bu[a] * bv[b];
      D.row(r) = rows[j][k].transpose();
      if (rows.weighted()) {  // min sum w |S - D|^2: each equation scaled by sqrt(w)
        const double sw = std::sqrt(rows.row_weights(j)[k]);
        A.row(r) *= sw;
        D.row(r) *= sw;
      }
    }
  }
  return A.householderQr().solve(D);
}

double largest_difference(const Surface& s, const Eigen::MatrixX3d& x) {
  double d = 0;
  for (std::size_t k = 0; k < s.control.size(); ++k)
    d = std::max(d, (s.control[k] - x.row(static_cast<long>(k)).transpose()).cwiseAbs().maxCoeff());
  return d;
}

TEST(TensorLsq, RaggedRowsEqualTheDenseReferenceWithAndWithoutConjugateGradients) {
  const Rows rows = ragged_rows(60, 7);
  for (Parametrization rule : {Parametrization::kChord, Parametrization::kCentripetal}) {
    // 30 x 44: beyond the band's bound, so conjugate gradients (at most 3/4 of the shortest
    // row's 40 points along u) or the sparse factorisation; the others factorised as a band.
    for (const auto& [nu, nv] :
         {std::pair{30, 44}, std::pair{20, 20}, std::pair{12, 25}, std::pair{8, 6}}) {
      Eigen::MatrixX3d ref;
      for (bool iterative : {true, false}) {
        TensorSpec spec;
        spec.rule = rule;
        spec.iterative = iterative;
        TensorProblem prob(rows, spec);
        const bool band = solves_as_band(spec, nu, nv);
        EXPECT_EQ(band, nu != 30) << "the pairs no longer cover every path of the solve";
        SCOPED_TRACE(std::to_string(nu) + " x " + std::to_string(nv) +
                     (band        ? " as a band"
                      : iterative ? " with CG"
                                  : " factorised"));
        Surface s;
        ASSERT_TRUE(prob.solve(nu, nv, s));
        if (ref.size() == 0) ref = dense_reference(rows, prob.u_at(nu), prob.v_at(nv), nu, nv, 3);
        // The data spans 100: control points to 1e-7 of it (CG stops at 1e-11 of the residual).
        EXPECT_LT(largest_difference(s, ref), 1e-5);
      }
    }
  }
}

TEST(TensorLsq, ClosedRowsOrClosedAcrossEqualTheDenseReferenceAsABand) {
  // The band's ordering wraps the closed direction inside its blocks (v-major where u is
  // closed, u-major where v is closed); the wrapped basis functions' products must land on
  // the same unknowns as the dense design matrix's.
  for (const bool cu : {true, false}) {
    const Rows rows = tube_rows(24, 5, cu);
    TensorSpec spec;
    spec.rule = Parametrization::kChord;
    spec.closed_u = cu;
    spec.closed_v = !cu;
    TensorProblem prob(rows, spec);
    for (const auto& [nu, nv] : {std::pair{14, 9}, std::pair{6, 12}, std::pair{20, 8}}) {
      SCOPED_TRACE(std::to_string(nu) + " x " + std::to_string(nv) +
                   (cu ? " closed u" : " closed v"));
      ASSERT_TRUE(solves_as_band(spec, nu, nv));
      Surface s;
      ASSERT_TRUE(prob.solve(nu, nv, s));
      const Eigen::MatrixX3d ref =
          dense_reference(rows, prob.u_at(nu), prob.v_at(nv), nu, nv, 3, cu, !cu);
      EXPECT_LT(largest_difference(s, ref), 1e-5);
    }
  }
}

TEST(TensorLsq, WeightedRowsEqualTheDenseWeightedReference) {
  Rows rows = ragged_rows(24, 11);
  std::vector<double> w(rows.total_points());
  for (std::size_t k = 0; k < w.size(); ++k) w[k] = 0.5 + static_cast<double>((k * 7) % 10);
  rows.set_weights(w);
  for (Parametrization rule : {Parametrization::kPaper, Parametrization::kChord}) {
    TensorSpec spec;
    spec.rule = rule;
    TensorProblem prob(rows, spec);
    for (const auto& [nu, nv] : {std::pair{20, 18}, std::pair{9, 7}}) {
      Surface s;
      ASSERT_TRUE(prob.solve(nu, nv, s));
      const Eigen::MatrixX3d ref = dense_reference(rows, prob.u_at(nu), prob.v_at(nv), nu, nv, 3);
      EXPECT_LT(largest_difference(s, ref), 1e-5) << nu << " x " << nv;
      // And the weights change it: not the unweighted fit.
      Rows plain = rows;
      plain.set_weights({});
      TensorProblem unweighted(plain, spec);
      Surface p;
      ASSERT_TRUE(unweighted.solve(nu, nv, p));
      EXPECT_GT(largest_difference(p, ref), 1e-3);
    }
  }
}

TEST(TensorLsq, GridEvenlySpacedAlongItsRowsSolvesSeparablyAtTheChordRule) {
  // Every row has the same chord positions (the same x spacing, the same curve shape), so the
  // separable solve applies; its surface must still be the least-squares one.
  Rows rows;
  for (int j = 0; j < 25; ++j) {
    for (int k = 0; k < 50; ++k)
      rows.push_point(Point(2.0 * k, 3.0 * j, std::sin(0.2 * k) + 0.1 * j));
    rows.end_row();
  }
  TensorSpec spec;
  spec.rule = Parametrization::kChord;
  TensorProblem prob(rows, spec);
  // The separable solve's cost model (linear in the unknowns) tells it apart.
  EXPECT_LT(prob.cost(30, 20), 1e5);
  Surface s;
  ASSERT_TRUE(prob.solve(30, 20, s));
  const Eigen::MatrixX3d ref = dense_reference(rows, prob.u_at(30), prob.v_at(20), 30, 20, 3);
  EXPECT_LT(largest_difference(s, ref), 1e-8);
}

TEST(KronPcg, ExactOnAKroneckerSystem) {
  // A = G (x) H with unknown (i, l) numbered i * nv + l: the preconditioner is A^-1 itself,
  // so CG is done in one step and gives A^-1 b.
  const int nu = 9, nv = 7;
  auto band = [](int n, double diag, double off) {
    Eigen::SparseMatrix<double> M(n, n);
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < n; ++i) {
      t.emplace_back(i, i, diag + 0.1 * i);
      if (i + 1 < n) t.emplace_back(i, i + 1, off);
    }
    M.setFromTriplets(t.begin(), t.end());
    return M;  // upper triangle of a symmetric positive definite band
  };
  const Eigen::SparseMatrix<double> G = band(nu, 2.0, 0.7), H = band(nv, 3.0, -1.1);
  const Eigen::MatrixXd Gd = Eigen::MatrixXd(G).selfadjointView<Eigen::Upper>();
  const Eigen::MatrixXd Hd = Eigen::MatrixXd(H).selfadjointView<Eigen::Upper>();
  Eigen::MatrixXd K(nu * nv, nu * nv);
  for (int i = 0; i < nu; ++i)
    for (int i2 = 0; i2 < nu; ++i2) K.block(i * nv, i2 * nv, nv, nv) = Gd(i, i2) * Hd;
  const Eigen::MatrixXd Ku = K.triangularView<Eigen::Upper>();
  const Eigen::SparseMatrix<double> A = Ku.sparseView();
  Eigen::MatrixX3d b = Eigen::MatrixX3d::Random(nu * nv, 3);
  Eigen::MatrixX3d x;
  int iterations = -1;
  ASSERT_TRUE(solve_kron_pcg(A, b, G, H, x, &iterations));
  EXPECT_LE(iterations, 1);
  EXPECT_LT((K * x - b).cwiseAbs().maxCoeff(), 1e-10);
}

}  // namespace
}  // namespace sfit::detail
