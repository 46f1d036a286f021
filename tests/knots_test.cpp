#include "knots.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sfit {
namespace {

TEST(Knots, ClampedUniformMatchesMethodSection2) {
  // Order 4 (degree 3), 7 control points: 0 0 0 0 1 2 3 4 4 4 4.
  EXPECT_EQ(clamped_uniform_knots(3, 7), (std::vector<double>{0, 0, 0, 0, 1, 2, 3, 4, 4, 4, 4}));
  // Bezier: count == degree + 1.
  EXPECT_EQ(clamped_uniform_knots(2, 3), (std::vector<double>{0, 0, 0, 1, 1, 1}));
  for (int p = 1; p <= 20; ++p)
    for (int n = p + 1; n < p + 12; ++n) {
      const auto k = clamped_uniform_knots(p, n);
      ASSERT_EQ(k.size(), static_cast<std::size_t>(n + p + 1));
      EXPECT_EQ(k[p], 0.0);
      EXPECT_EQ(k[n], domain_end(p, n, false));
    }
}

TEST(Knots, PeriodicUniformIsStoredInFull) {
  // 5 distinct control points, degree 2: 5 + 2 stored, knots -2 ... 7, domain [0, 5].
  const auto k = periodic_uniform_knots(2, 5);
  ASSERT_EQ(k.size(), 5u + 2 * 2 + 1);
  EXPECT_EQ(k.front(), -2);
  EXPECT_EQ(k.back(), 7);
  EXPECT_EQ(k[2], 0.0);
  EXPECT_EQ(k[5 + 2], domain_end(2, 5, true));
}

TEST(Knots, GrevilleOfClampedVectorSpansTheDomain) {
  for (int p = 1; p <= 7; ++p)
    for (int n = p + 1; n < 20; ++n) {
      EXPECT_DOUBLE_EQ(greville(p, n, false, 0), 0.0);
      EXPECT_DOUBLE_EQ(greville(p, n, false, n - 1), n - p);
      for (int i = 1; i < n; ++i) EXPECT_GT(greville(p, n, false, i), greville(p, n, false, i - 1));
    }
  // Degree 3, 7 points: knot averages of (0,0,0),(0,0,1),(0,1,2),(1,2,3),(2,3,4),(3,4,4),(4,4,4).
  const double expect[] = {0, 1.0 / 3, 1, 2, 3, 11.0 / 3, 4};
  for (int i = 0; i < 7; ++i) EXPECT_DOUBLE_EQ(greville(3, 7, false, i), expect[i]);
}

TEST(Knots, PeriodicGrevilleAvoidsKnotsForEvenDegree) {
  // Odd degree: Greville points on knots (integers); even degree: mid-way between knots.
  for (int i = 0; i < 6; ++i) {
    EXPECT_DOUBLE_EQ(greville(3, 6, true, i), (i - 1 + 6) % 6);
    const double g2 = greville(2, 6, true, i);
    EXPECT_DOUBLE_EQ(g2 - std::floor(g2), 0.5);
  }
}

TEST(Knots, GrevilleAtInterpolatesLinearly) {
  // Greville 0, 1/3, 1, 2, 3, 11/3, 4: index 2.5 lies half-way between 1 and 2.
  EXPECT_DOUBLE_EQ(greville_at(3, 7, false, 2.5), 1.5);
  EXPECT_DOUBLE_EQ(greville_at(3, 7, false, 0.5), 1.0 / 6);
  EXPECT_DOUBLE_EQ(greville_at(3, 7, false, 6), 4);
}

}  // namespace
}  // namespace sfit
