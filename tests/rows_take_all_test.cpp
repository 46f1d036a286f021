// The two stages with all of T for the rows and columns that interpolate them
// (SurfaceFitter::rows_take_all(), docs/method.md 7.2): the default tries it where no pair of
// the search beat the two stages and theirs has more control points than points. Data: an
// airborne-LiDAR-like strip of scan lines over flat-roofed buildings, the lines at 30 degrees
// to the strip's edges so each is clipped by them (rows of 4 ... 140 points); the roofs jump by
// more than T within a point spacing, so the columns need a control point per line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>

#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

using test::Uniform;

Rows roofs(int lines) {
  Uniform r(3);
  struct Box {
    double x, y, w, d, h;
  };
  std::vector<Box> boxes;
  for (int k = 0; k < 8; ++k)
    boxes.push_back({r(10, 190), r(10, 190), r(8, 25), r(8, 25), r(5, 15)});
  auto height = [&](double x, double y) {
    double z = 10 * std::sin(x / 60) * std::cos(y / 80);
    for (const Box& b : boxes)
      if (std::abs(x - b.x) < b.w / 2 && std::abs(y - b.y) < b.d / 2) z += b.h;
    return z;
  };
  const double a = std::numbers::pi / 6, dx = std::cos(a), dy = std::sin(a);
  Rows rows;
  for (int j = 0; j < lines; ++j) {
    const double off = -100 + 273.0 * j / (lines - 1);
    std::vector<Point> row;
    for (double t = -400; t < 400; t += 2.0) {
      const double x = -off * dy + t * dx, y = off * dx + t * dy;
      if (x >= 0 && x <= 200 && y >= 0 && y <= 200) row.emplace_back(x, y, height(x, y));
    }
    if (row.size() < 4) continue;
    for (const Point& p : row) rows.push_point(p);
    rows.end_row();
  }
  return rows;
}

TEST(RowsTakeAll, FewerControlPointsThanTheHalvesOnJumpingRows) {
  const Rows rows = roofs(80);
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-2);
  const FitResult d = fit_surface(rows, o);
  FitOptions o1 = o;
  o1.method = FitMethod::kSfit01;
  const FitResult two = fit_surface(rows, o1);
  std::printf("[ measured ] %zu points in %zu lines: default %d x %d (%s), sfit01 %d x %d\n",
              rows.total_points(), rows.size(), d.surface.count_u, d.surface.count_v,
              d.report.stop_reason.c_str(), two.surface.count_u, two.surface.count_v);
  ASSERT_NE(d.report.stop_reason.find("the rows took all of T"), std::string::npos)
      << d.report.stop_reason;
  // Fewer control points than the paper's halves, T held at every point (an independent
  // evaluation), no fold. The rows at T (95 x 78, one per line across) still have more control
  // points than the 5,798 points, so the fallback below the points (docs/method.md 7.12)
  // replaces them (measured: 57 x 39), naming them in its stop reason.
  EXPECT_LT(d.surface.count_u * d.surface.count_v, two.surface.count_u * two.surface.count_v);
  EXPECT_LT(static_cast<std::size_t>(d.surface.count_u) * d.surface.count_v, rows.total_points());
  EXPECT_NE(d.report.stop_reason.find("in place of 95 x 78"), std::string::npos)
      << d.report.stop_reason;
  const Point dev = test::reference_deviation(d, rows);
  for (int k = 0; k < 3; ++k) EXPECT_LE(dev[k], o.tolerance[k]) << k;
  EXPECT_TRUE(d.report.within_tolerance);
  EXPECT_EQ(d.report.fold, 0.0);
  // The stop reason gives the halves' count, which --method sfit01 returns.
  EXPECT_NE(d.report.stop_reason.find("(" + std::to_string(two.surface.count_u) + " x " +
                                      std::to_string(two.surface.count_v) + " with T/2 each)"),
            std::string::npos)
      << d.report.stop_reason;
}

}  // namespace
}  // namespace sfit
