// The stretched pass's parameters (below_points_dense.h, docs/method.md 7.12): one monotone
// map of [0, 1] onto itself whose slope near a point that missed T is that point's miss ratio
// times its slope far from every miss.
#include <gtest/gtest.h>

#include <vector>

#include "below_points_dense.h"

namespace sfit {
namespace {

// 1,001 fractions evenly over [0, 1].
std::vector<double> even() {
  std::vector<double> f(1001);
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = static_cast<double>(k) / 1000;
  return f;
}

TEST(BelowPointsDense, NoMissLeavesTheFractionsAsTheyAre) {
  std::vector<double> f = even();
  const std::vector<double> before = f;
  detail::stretch_where_missed(std::vector<double>(f.size(), 0.9), 10, f);
  EXPECT_EQ(f, before);
}

TEST(BelowPointsDense, AMissStretchesItsSpansByItsRatioAndKeepsTheOrderAndTheEnds) {
  std::vector<double> f = even();
  std::vector<double> ratio(f.size(), 0.5);
  ratio[500] = 4;  // the point at 0.5 missed T by 4x; spans are 0.1 wide (10)
  detail::stretch_where_missed(ratio, 10, f);
  EXPECT_EQ(f.front(), 0.0);
  EXPECT_EQ(f.back(), 1.0);
  for (std::size_t k = 1; k < f.size(); ++k) ASSERT_LT(f[k - 1], f[k]) << k;
  // Within one span of the miss the map is 4 times as steep as beyond two spans.
  const double near = f[520] - f[480], far = f[90] - f[50];
  EXPECT_NEAR(near / far, 4.0, 0.05);
  // Symmetric about the miss.
  EXPECT_NEAR(f[500], 0.5, 1e-3);
  // Between one and two spans, the slope falls linearly: steeper than far, less than near.
  const double between = f[660] - f[620];
  EXPECT_GT(between, far * 1.2);
  EXPECT_LT(between, near * 0.8);
}

}  // namespace
}  // namespace sfit
