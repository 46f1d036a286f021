#include "sfit/parametrization.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sfit/knots.h"

namespace sfit {
namespace {

TEST(Parametrization, OpenEndsOnDomainAndGrevilleWhenInterpolating) {
  for (int p = 1; p <= 6; ++p)
    for (int n = p + 1; n <= 25; n += 3)
      for (int N : {n, n + 1, 2 * n + 3}) {
        const auto t = paper_parameters(p, n, false, N);
        ASSERT_EQ(t.size(), static_cast<std::size_t>(N));
        EXPECT_EQ(t.front(), 0.0);
        EXPECT_EQ(t.back(), domain_end(p, n, false));
        for (int j = 1; j < N; ++j) EXPECT_GT(t[j], t[j - 1]);
        if (N == n) {
          for (int j = 0; j < N; ++j) EXPECT_NEAR(t[j], greville(p, n, false, j), 1e-12);
        }
      }
}

TEST(Parametrization, EveryKnotSpanGetsAParameter) {
  // METHOD.md 3: every non-empty knot span holds at least one t (Schoenberg-Whitney).
  for (int p = 1; p <= 5; ++p)
    for (int n = p + 1; n <= 30; ++n)
      for (int N = n; N <= n + 7; ++N) {
        const auto t = paper_parameters(p, n, false, N);
        for (int span = 0; span < n - p; ++span) {
          bool hit = false;
          for (double x : t) hit = hit || (x >= span && x <= span + 1);
          EXPECT_TRUE(hit) << "p=" << p << " n=" << n << " N=" << N << " span " << span;
        }
      }
}

TEST(Parametrization, PaperFormulaOnASmallCase) {
  // N = 5 points, order 4 (degree 3), N_u = 4: A = 3/4; Greville 0, 1/3, 2/3, 1.
  // t_j = Greville at fractional index A*j: 0, 0.25, 0.5, 0.75, 1.
  const auto t = paper_parameters(3, 4, false, 5);
  const double expect[] = {0, 0.25, 0.5, 0.75, 1};
  for (int j = 0; j < 5; ++j) EXPECT_NEAR(t[j], expect[j], 1e-15);
}

TEST(Parametrization, PeriodicIsUniformAndHitsGreville) {
  for (int p : {1, 2, 3, 4}) {
    const auto t = paper_parameters(p, 8, true, 8);
    for (int j = 0; j < 8; ++j) {
      bool found = false;
      for (int i = 0; i < 8; ++i) found = found || std::abs(t[j] - greville(p, 8, true, i)) < 1e-12;
      EXPECT_TRUE(found) << "degree " << p;
    }
    const auto u = paper_parameters(p, 8, true, 20);
    // Uniform steps around the loop (parameters are reduced into [0, 8)).
    for (int j = 1; j < 20; ++j) EXPECT_NEAR(std::fmod(u[j] - u[j - 1] + 8, 8.0), 8.0 / 20, 1e-12);
  }
}

TEST(Parametrization, ReparameterMapSendsSamplesToNewGreville) {
  for (bool periodic : {false, true}) {
    const ReparameterMap m(3, 7, 3, 12, periodic);
    ASSERT_EQ(m.samples().size(), 12u);
    for (std::size_t l = 0; l < 12; ++l) EXPECT_NEAR(m(m.samples()[l]), m.targets()[l], 1e-12);
    if (!periodic) {
      EXPECT_EQ(m(0.0), 0.0);
      EXPECT_EQ(m(domain_end(3, 7, false)), domain_end(3, 12, false));
    }
  }
  // Same count and degree: the identity.
  const ReparameterMap id(3, 9, 3, 9, false);
  for (double t : {0.0, 0.4, 2.2, 5.9, 6.0}) EXPECT_NEAR(id(t), t, 1e-12);
}

}  // namespace
}  // namespace sfit
