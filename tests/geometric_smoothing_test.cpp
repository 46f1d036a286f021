// The geometric rule's smoothness term at a small T (geometric_search.cpp, search_geometric();
// docs/method.md 7.9): scan lines clipped by a disc, whose rows wander across (each row alone
// needs all its points at T), on a smooth height. The term's default weight pulls on the spans
// that hold data by an amount that does not shrink with T; at 1e-5 of the diagonal no pair
// held with it, and the default returned more control points than points. The search again
// with the weight lowered from the first pair on finds a small surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>

#include "fit_frame.h"
#include "geometric_search.h"
#include "search_frame.h"
#include "sfit/surface_fit.h"
#include "surface_distance.h"
#include "test_support.h"

namespace sfit {
namespace {

double height(double x, double y) {
  return 0.35 * std::exp(-((x - 0.3) * (x - 0.3) + (y + 0.2) * (y + 0.2)) / 0.18) -
         0.25 * std::exp(-((x + 0.4) * (x + 0.4) + (y - 0.35) * (y - 0.35)) / 0.09) +
         0.08 * std::sin(2.5 * x + 1.3 * y);
}

// 50 lines y = const across the unit disc, a point every ~0.01 along x at random, each point's
// y off its line by up to 2e-3 (a scanner's wander): the rows are no iso-lines of any surface.
Rows wandering_clipped_lines() {
  test::Uniform r(23);
  Rows rows;
  for (int j = 0; j < 50; ++j) {
    const double y = -0.97 + 1.94 * j / 49, h = std::sqrt(1 - y * y);
    const int n = std::max(4, static_cast<int>(h / 0.005));
    std::vector<double> x(static_cast<std::size_t>(n));
    for (double& t : x) t = r(-h, h);
    std::sort(x.begin(), x.end());
    for (double t : x) {
      const double w = y + r(-2e-3, 2e-3);
      rows.push_point(Point(t, w, height(t, w)));
    }
    rows.end_row();
  }
  return rows;
}

TEST(GeometricSmoothing, ASmallTHoldsFarBelowThePointsWithTheWeightLowered) {
  const Rows rows = wandering_clipped_lines();
  const FitOptions o = test::at(rows, 1e-5);
  const long points = static_cast<long>(rows.total_points());
  // The default weight alone: nothing below a quarter of the points held.
  const detail::Frame fr(rows, o);
  long tried = 0;
  EXPECT_FALSE(detail::search_geometric_counted(fr, o, points / 4, detail::kCorrectionRounds, tried,
                                                detail::BasePlane::kBest, 0));
  EXPECT_GT(tried, 0);
  // The default: the geometric rule, searched again with the weight lowered.
  const FitResult d = fit_surface(rows, o);
  EXPECT_EQ(d.report.parametrization, Parametrization::kGeometric);
  EXPECT_NE(d.report.stop_reason.find("weight lowered from the first pair on"), std::string::npos)
      << d.report.stop_reason;
  EXPECT_LT(test::size_of(d) * 4, points) << d.surface.count_u << " x " << d.surface.count_v;
  EXPECT_EQ(d.report.fold, 0.0);
  // T at every point (the independent evaluator at the points' parameters), and within T of
  // the surface by an independent closest-point search.
  EXPECT_TRUE(d.report.within_tolerance);
  const Point dev = test::reference_deviation(d, rows);
  for (int a = 0; a < 3; ++a) EXPECT_LE(dev[a], o.tolerance[a] * (1 + 1e-9)) << "axis " << a;
  for (std::size_t k = 0; k < rows.total_points(); k += 7)
    ASSERT_LE(test::distance_to_surface(d.surface, rows.points()[k]), o.tolerance.x() * (1 + 1e-9))
        << "point " << k;
}

}  // namespace
}  // namespace sfit
