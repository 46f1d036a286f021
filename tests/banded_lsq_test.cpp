#include "banded_lsq.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstring>
#include <random>

namespace sfit::detail {
namespace {

// Random banded (cyclic when periodic) weighted least-squares problems against Eigen's dense
// column-pivoting QR on the same matrix.
void compare_with_dense(int n, int w, bool periodic, int rows, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, n);
  Eigen::MatrixXd B(rows, 3);
  BandedLeastSquares lsq(n, w, periodic);
  for (int r = 0; r < rows; ++r) {
    const int first = periodic ? r % n : std::min(r * (n - w + 1) / rows, n - w);
    std::vector<double> c(w);
    for (int i = 0; i < w; ++i) c[i] = U(rng);
    const Point rhs(U(rng), U(rng), U(rng));
    const double weight = 0.5 + std::abs(U(rng));
    lsq.add(first, c.data(), rhs, weight);
    for (int i = 0; i < w; ++i) A(r, (first + i) % n) += weight * c[i];
    B.row(r) = weight * rhs.transpose();
  }
  std::vector<Point> x;
  ASSERT_TRUE(lsq.solve(x));
  const Eigen::MatrixXd X = A.colPivHouseholderQr().solve(B);
  for (int i = 0; i < n; ++i)
    EXPECT_NEAR((x[i] - X.row(i).transpose()).norm(), 0.0, 1e-9 * (1 + X.norm()))
        << "n=" << n << " w=" << w << " periodic=" << periodic << " i=" << i;
}

TEST(BandedLeastSquares, MatchesDenseQrOpen) {
  compare_with_dense(10, 4, false, 40, 1);
  compare_with_dense(30, 2, false, 31, 2);
  compare_with_dense(25, 8, false, 100, 3);
}

TEST(BandedLeastSquares, MatchesDenseQrPeriodic) {
  compare_with_dense(10, 4, true, 40, 4);
  compare_with_dense(5, 4, true, 25, 5);  // count == width - 1 + 2: the wrap touches most columns
  compare_with_dense(4, 4, true, 16, 6);  // count == width: every equation touches every unknown
  compare_with_dense(40, 6, true, 120, 7);
}

TEST(BandedLeastSquares, DetectsAnUndeterminedUnknown) {
  // Unknown 5 appears in no equation.
  BandedLeastSquares lsq(6, 2, false);
  const double c[2] = {1, 1};
  for (int r = 0; r < 4; ++r) lsq.add(r, c, Point(1, 2, 3));
  std::vector<Point> x;
  EXPECT_FALSE(lsq.solve(x));
}

}  // namespace
}  // namespace sfit::detail

namespace sfit::detail {
namespace {

TEST(BandedLeastSquares, ReplayIsBitIdenticalToFactorisingAfresh) {
  for (bool periodic : {false, true}) {
    const int n = 12, w = 4, rows = 50;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> U(-1, 1);
    std::vector<std::vector<double>> coef(rows, std::vector<double>(w));
    std::vector<int> first(rows);
    for (int r = 0; r < rows; ++r) {
      first[r] = periodic ? r % n : std::min(r * (n - w + 1) / rows, n - w);
      for (double& c : coef[r]) c = U(rng);
    }
    BandedLeastSquares shared(n, w, periodic);
    shared.record_rotations();
    for (int r = 0; r < rows; ++r) shared.add(first[r], coef[r].data(), Point::Zero());
    for (int trial = 0; trial < 3; ++trial) {
      std::vector<Point> rhs(rows);
      for (Point& p : rhs) p = Point(U(rng), U(rng), U(rng));
      BandedLeastSquares fresh(n, w, periodic);
      for (int r = 0; r < rows; ++r) fresh.add(first[r], coef[r].data(), rhs[r]);
      std::vector<Point> a, b, z;
      ASSERT_TRUE(fresh.solve(a));
      ASSERT_TRUE(shared.replay(rhs.data(), b, z));
      ASSERT_EQ(a.size(), b.size());
      EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(Point))) << periodic;
    }
  }
}

}  // namespace
}  // namespace sfit::detail
