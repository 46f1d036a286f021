#include "banded_cholesky.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace sfit::detail {
namespace {

// The factorisation as scattered_lsq.cpp wrote it before the four-row AVX2 path: one entry at a
// time, four partial sums. Both paths must give these bits.
bool reference(std::vector<double>& L, long N, long b, double floor) {
  const long w1 = b + 1;
  for (long r = 0; r < N; ++r) {
    double* Lr = L.data() + r * w1 - r + b;
    for (long c = std::max(0L, r - b); c <= r; ++c) {
      const double* Lc = L.data() + c * w1 - c + b;
      double s4[4] = {0, 0, 0, 0};
      long k = std::max(0L, r - b);
      for (; k + 4 <= c; k += 4)
        for (int e = 0; e < 4; ++e) s4[e] += Lr[k + e] * Lc[k + e];
      for (; k < c; ++k) s4[0] += Lr[k] * Lc[k];
      const double sum = Lr[c] - ((s4[0] + s4[1]) + (s4[2] + s4[3]));
      if (c == r) {
        if (!(sum > floor)) return false;
        Lr[c] = std::sqrt(sum);
      } else {
        Lr[c] = sum / Lc[c];
      }
    }
  }
  return true;
}

// A random symmetric positive definite band matrix (diagonally dominant) in the band store.
std::vector<double> random_band(long N, long b, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<double> A(static_cast<std::size_t>(N * (b + 1)), 0.0);
  for (long r = 0; r < N; ++r)
    for (long c = std::max(0L, r - b); c <= r; ++c)
      A[r * (b + 1) + c - r + b] = c == r ? 2.0 * b + 1 + U(rng) : U(rng);
  return A;
}

TEST(BandedCholesky, SameBitsAsOneEntryAtATimeAndFactorsTheMatrix) {
  // Row counts around multiples of four, bands wider and narrower than the rows.
  for (const auto& [N, b] : std::vector<std::pair<long, long>>{{1, 0},
                                                               {3, 2},
                                                               {4, 3},
                                                               {5, 1},
                                                               {7, 6},
                                                               {9, 4},
                                                               {17, 16},
                                                               {64, 5},
                                                               {130, 39},
                                                               {203, 90},
                                                               {258, 126},
                                                               {301, 37}}) {
    const std::vector<double> A = random_band(N, b, static_cast<unsigned>(N * 131 + b));
    std::vector<double> L = A, R = A, P = A;
    ASSERT_TRUE(banded_cholesky(L.data(), N, b, 1e-13));
    ASSERT_TRUE(banded_cholesky(P.data(), N, b, 1e-13, false));  // the plain loop on any CPU
    ASSERT_TRUE(reference(R, N, b, 1e-13));
    EXPECT_EQ(0, std::memcmp(L.data(), R.data(), L.size() * sizeof(double))) << N << " " << b;
    EXPECT_EQ(0, std::memcmp(P.data(), R.data(), P.size() * sizeof(double))) << N << " " << b;
    // L L^T is A.
    double worst = 0;
    for (long r = 0; r < N; ++r)
      for (long c = std::max(0L, r - b); c <= r; ++c) {
        double s = 0;
        for (long k = std::max(0L, r - b); k <= c; ++k)
          s += L[r * (b + 1) + k - r + b] * L[c * (b + 1) + k - c + b];
        worst = std::max(worst, std::abs(s - A[r * (b + 1) + c - r + b]));
      }
    EXPECT_LT(worst, 1e-12 * (2.0 * b + 2)) << N << " " << b;
  }
}

TEST(BandedCholesky, ThreeRightHandSidesGiveTheSameBitsAsOnePerAxisAndSolve) {
  // The Point substitution (the AVX2 path where the CPU has it) against the scalar template run
  // on each axis alone: the same bits; and L L^T x = y.
  for (const auto& [N, b] : std::vector<std::pair<long, long>>{
           {1, 0}, {3, 2}, {5, 1}, {9, 4}, {64, 5}, {130, 39}, {203, 90}}) {
    const std::vector<double> A = random_band(N, b, static_cast<unsigned>(N * 17 + b));
    std::vector<double> L = A;
    ASSERT_TRUE(banded_cholesky(L.data(), N, b, 1e-13));
    std::mt19937 rng(static_cast<unsigned>(N + b));
    std::uniform_real_distribution<double> U(-1, 1);
    std::vector<Eigen::Vector3d> y(static_cast<std::size_t>(N));
    for (auto& p : y) p = Eigen::Vector3d(U(rng), U(rng), U(rng));
    std::vector<Eigen::Vector3d> x = y, t = y;
    banded_substitute(L.data(), N, b, x.data());
    banded_substitute(L.data(), N, b, t.data(), false);  // the template on any CPU
    for (int a = 0; a < 3; ++a) {
      std::vector<double> s(static_cast<std::size_t>(N));
      for (long r = 0; r < N; ++r) s[r] = y[r][a];
      banded_substitute(L.data(), N, b, s.data());
      for (long r = 0; r < N; ++r) {
        EXPECT_EQ(0, std::memcmp(&s[r], &x[r][a], sizeof(double))) << N << " " << b << " " << r;
        EXPECT_EQ(0, std::memcmp(&s[r], &t[r][a], sizeof(double))) << N << " " << b << " " << r;
      }
    }
    // A x = y (A symmetric, in the band store's lower triangle).
    double worst = 0;
    for (long r = 0; r < N; ++r) {
      Eigen::Vector3d s = Eigen::Vector3d::Zero();
      for (long c = std::max(0L, r - b); c <= std::min(N - 1, r + b); ++c)
        s += A[std::max(r, c) * (b + 1) + std::min(r, c) - std::max(r, c) + b] * x[c];
      worst = std::max(worst, (s - y[r]).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst, 1e-12 * (2.0 * b + 2)) << N << " " << b;
  }
}

TEST(BandedCholesky, FailsAtAPivotAtRoundOff) {
  // Rows 4 and 5 (one of the four-row blocks) equal: the second's pivot is round-off.
  const long N = 12, b = 11;
  std::vector<double> A = random_band(N, b, 7);
  for (long c = 0; c < N; ++c) {
    auto at = [&](long r, long k) -> double& {
      return A[std::max(r, k) * (b + 1) + std::min(r, k) - std::max(r, k) + b];
    };
    if (c != 5) at(5, c) = at(4, c);
  }
  A[5 * (b + 1) + 5 - 5 + b] = A[4 * (b + 1) + 4 - 4 + b];
  A[5 * (b + 1) + 4 - 5 + b] = A[4 * (b + 1) + 4 - 4 + b];
  std::vector<double> L = A, R = A;
  EXPECT_FALSE(reference(R, N, b, 1e-9));
  EXPECT_FALSE(banded_cholesky(L.data(), N, b, 1e-9));
  std::vector<double> P = A;
  EXPECT_FALSE(banded_cholesky(P.data(), N, b, 1e-9, false));
}

}  // namespace
}  // namespace sfit::detail
