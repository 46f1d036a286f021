#include "rerepresent.h"
#include "parameters.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sfit {
namespace {

std::vector<Point> bumpy(int n) {
  std::vector<Point> pts;
  for (int k = 0; k < n; ++k) {
    const double s = static_cast<double>(k) / (n - 1);
    pts.emplace_back(s, std::sin(9 * s), std::exp(s));
  }
  return pts;
}

TEST(Rerepresent, HoldsTheBoundOnACommonCount) {
  const auto pts = bumpy(60);
  const Point bound = Point::Constant(0.01);
  const CurveFit f = fit_curve(pts, {3, false, bound, CountSearch::kLinear});
  for (int count = f.curve.count(); count <= f.curve.count() + 15; ++count) {
    const Rerepresentation r = rerepresent(f, pts, 3, count, false, bound);
    ASSERT_TRUE(r.holds) << count;
    EXPECT_EQ(r.curve.count(), count);
    for (std::size_t k = 0; k < pts.size(); ++k)
      EXPECT_TRUE(
          ((r.curve.evaluate(r.parameters[k]) - pts[k]).cwiseAbs().array() <= bound.array()).all())
          << "count " << count << " point " << k;
  }
}

TEST(Rerepresent, SameCountIsTheSameCurve) {
  const auto pts = bumpy(40);
  const CurveFit f = fit_curve(pts, {3, false, Point::Constant(0.01), CountSearch::kLinear});
  const Rerepresentation r = rerepresent(f, pts, 3, f.curve.count(), false, Point::Constant(0.01));
  EXPECT_EQ(r.repair_rounds, 0);
  for (int i = 0; i < f.curve.count(); ++i)
    EXPECT_NEAR((r.curve.control[i] - f.curve.control[i]).norm(), 0, 1e-12);
}

TEST(Rerepresent, RepairKeepsInterpolationOfAShortRow) {
  // A 4-point row interpolated at T = 0, re-represented on 11 control points: the paper's
  // sampling alone moves the points; the repair must put them back to round-off.
  const std::vector<Point> pts = {Point(0, 0, 0), Point(1, 3, 0), Point(2, -1, 1), Point(3, 0, 0)};
  const CurveFit f = fit_curve(pts, {3, false, Point::Zero(), CountSearch::kFast});
  const Rerepresentation r = rerepresent(f, pts, 3, 11, false, Point::Constant(1e-12));
  ASSERT_TRUE(r.holds);
  for (int k = 0; k < 4; ++k)
    EXPECT_NEAR((r.curve.evaluate(r.parameters[k]) - pts[k]).norm(), 0, 1e-11);
}

TEST(Rerepresent, TargetParametersAreUsed) {
  const auto pts = bumpy(30);
  const CurveFit f = fit_curve(pts, {2, false, Point::Constant(0.02), CountSearch::kLinear});
  // The columns' case: the paper's parameters for the new count, common to all columns.
  // The row needs 17 control points; on 20 with these parameters the paper's sampling alone
  // misses some points, and the repair brings them back.
  ASSERT_EQ(f.curve.count(), 17);
  const std::vector<double> target = paper_parameters(2, 20, false, 30);
  const Rerepresentation r = rerepresent(f, pts, 2, 20, false, Point::Constant(0.02), target);
  ASSERT_TRUE(r.holds);
  EXPECT_GT(r.repair_rounds, 0);
  EXPECT_EQ(r.parameters, target);
  for (int k = 0; k < 30; ++k)
    EXPECT_LE((r.curve.evaluate(target[k]) - pts[k]).cwiseAbs().maxCoeff(), 0.02) << k;
}

TEST(Rerepresent, RepairOfALongCurveHoldsTheBound) {
  // The columns' case at the length of 5,000 rows of a few points: a slightly rough column
  // interpolated (one control point per row), re-represented on 3 more at the paper's
  // parameters. Above 4096 control points the repair rounds add their equations in the order
  // of their first unknown (linear cost); the bound must hold at every point all the same.
  const int n = 5000;
  std::vector<Point> pts;
  unsigned state = 12345;
  auto noise = [&] {
    state = state * 1103515245u + 12345u;
    return static_cast<double>((state >> 8) & 0xffff) / 65536.0 - 0.5;
  };
  for (int k = 0; k < n; ++k) {
    const double s = static_cast<double>(k) / (n - 1);
    pts.emplace_back(s, std::sin(9 * s) + 1e-4 * noise(), 1e-4 * noise());
  }
  const CurveFit f = fit_curve(pts, {3, false, Point::Zero(), CountSearch::kFast});
  ASSERT_EQ(f.curve.count(), n);
  const int count = n + 3;
  const Point bound = Point::Constant(1e-9);
  const std::vector<double> target = paper_parameters(3, count, false, n);
  const Rerepresentation r = rerepresent(f, pts, 3, count, false, bound, target);
  ASSERT_TRUE(r.holds);
  EXPECT_GT(r.repair_rounds, 0);
  EXPECT_EQ(r.parameters, target);
  for (int k = 0; k < n; ++k)
    EXPECT_LE((r.curve.evaluate(target[k]) - pts[k]).cwiseAbs().maxCoeff(), 1e-9) << k;
}

TEST(Rerepresent, PoleBecomesCoincidentControlPoints) {
  const std::vector<Point> pts = {Point(4, 5, 6)};
  const CurveFit f = fit_curve(pts, {3, true, Point::Zero(), CountSearch::kFast});
  const Rerepresentation r = rerepresent(f, pts, 3, 8, true, Point::Zero());
  ASSERT_TRUE(r.holds);
  ASSERT_EQ(r.curve.count(), 8);
  for (const Point& c : r.curve.control) EXPECT_EQ(c, Point(4, 5, 6));
}

}  // namespace
}  // namespace sfit
