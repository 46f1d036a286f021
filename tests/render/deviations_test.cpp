// Deviations for the deviation picture: at the fitted parameters (the report's) and at the
// closest surface point.
#include "sfit/render/deviations.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "picture_checks.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit::test {
namespace {

TEST(Deviations, AtTheFittedParametersTheyAreTheReports) {
  const Rows rows = load_rows(example("ship_px121_stations.rows"));
  const FitResult f = fit_at(rows, 0.2);
  const auto d = render::deviations_at_parameters(f.surface, rows, f.u, f.v_for_points());
  ASSERT_EQ(d.size(), rows.total_points());
  Point m = Point::Zero();
  for (const Point& p : d) m = m.cwiseMax(p.cwiseAbs());
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(m[a], f.report.max_deviation[a], 1e-12 * (1 + m[a]));
  const std::size_t worst = rows.offsets()[f.report.worst_row] + f.report.worst_index;
  EXPECT_NEAR((d[worst] - f.report.worst_deviation).norm(), 0, 1e-12);
}

TEST(Deviations, ClosestPointsOfACylinderAreRadial) {
  // A closed cylinder of radius 1 (rows are circles); points at radius 1 + h lie h from it.
  const Rows rows = sample_rows(
      [](double s, double t) {
        const double a = 2 * std::numbers::pi * s;
        return Point(std::cos(a), std::sin(a), 3 * t);
      },
      std::vector<int>(7, 40), true);
  const FitResult f = fit_at(rows, 1e-7, true);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi), z(0.3, 2.7), h(-0.2, 0.2);
  std::vector<Point> q;
  std::vector<double> off;
  for (int k = 0; k < 300; ++k) {
    const double a = angle(rng), r = 1 + h(rng);
    q.emplace_back(r * std::cos(a), r * std::sin(a), z(rng));
    off.push_back(r - 1);
  }
  const auto c = render::closest_points(f.surface, q);
  for (std::size_t k = 0; k < q.size(); ++k) {
    EXPECT_NEAR(c[k].deviation.norm(), std::abs(off[k]), 2e-5) << k;
    EXPECT_NEAR((f.surface.evaluate(c[k].u, c[k].v) - q[k] - c[k].deviation).norm(), 0, 1e-12);
    EXPECT_NEAR(c[k].deviation.z(), 0, 2e-5) << "radial, not along the axis";
  }
}

TEST(Deviations, ClosestIsNeverFartherThanAssigned) {
  const Rows rows = load_rows(example("iea3p4mw_blade_ragged9.rows"));
  const FitResult f = fit_at(rows, 0.02, true);
  const auto assigned = render::deviations_at_parameters(f.surface, rows, f.u, f.v_for_points());
  const auto closest = render::closest_points(f.surface, rows.points());
  for (std::size_t k = 0; k < assigned.size(); ++k)
    ASSERT_LE(closest[k].deviation.norm(), assigned[k].norm() + 1e-9) << "point " << k;
  // The rows' v recovered from their closest points are the fit's within a small fraction of
  // a knot span.
  const auto v = render::row_parameters(f.surface, rows, closest);
  for (std::size_t j = 0; j < rows.size(); ++j) EXPECT_NEAR(v[j], f.v[j], 0.05) << "row " << j;
}

TEST(Deviations, ToleranceRatioIsTheLargestShareOfAnAxis) {
  EXPECT_DOUBLE_EQ(render::tolerance_ratio(Point(0.1, -0.3, 0.05), Point(1, 1, 0.1), 0), 0.5);
  EXPECT_DOUBLE_EQ(render::tolerance_ratio(Point(0, 0, -2e-12), Point(1, 1, 0), 1e-12), 2.0);
  EXPECT_DOUBLE_EQ(render::tolerance_ratio(Point(0, 0, 0), Point(0, 0, 0), 0), 0.0);
}

}  // namespace
}  // namespace sfit::test
