// The geometric rule's base plane (geometric_params.h BasePlane, docs/method.md 7.9): over a
// height field whose best plane is tilted, the coordinate plane's parameters (the field's own
// x, y) against the best plane's, and the search that tries both.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdio>

#include "geometric_params.h"
#include "geometric_search.h"
#include "search_frame.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

using test::Uniform;

// bench/scan_cases.py's field: two bumps and a gentle wave; its best plane over the disk is
// tilted by about 12 degrees.
double field(double x, double y) {
  return 0.35 * std::exp(-((x - 0.3) * (x - 0.3) + (y + 0.2) * (y + 0.2)) / 0.18) -
         0.25 * std::exp(-((x + 0.4) * (x + 0.4) + (y - 0.35) * (y - 0.35)) / 0.09) +
         0.08 * std::sin(2.5 * x + 1.3 * y);
}

// Scan lines y = const clipped by the unit disk, points at random along x every ~0.02.
Rows clipped_scan_lines() {
  Uniform r(3);
  Rows rows;
  for (int j = 0; j < 60; ++j) {
    const double y = -0.98 + 1.96 * j / 59, h = std::sqrt(1 - y * y);
    const int n = std::max(3, static_cast<int>(2 * h / 0.02));
    std::vector<double> x(n);
    for (double& t : x) t = r(-h, h);
    std::sort(x.begin(), x.end());
    for (double t : x) rows.push_point(Point(t, y, field(t, y)));
    rows.end_row();
  }
  return rows;
}

// Over the coordinate plane each point's fractions are its x and y scaled to the data's box
// (rows along x: u follows x); over the tilted best plane they are not.
TEST(GeometricBasePlane, AxisPlaneGivesTheFieldsOwnCoordinates) {
  const Rows rows = clipped_scan_lines();
  const auto axis = detail::base_surface_fractions(rows, false, false, detail::BasePlane::kAxis);
  const auto best = detail::base_surface_fractions(rows, false, false);
  ASSERT_TRUE(axis && best);
  double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
  for (const Point& p : rows.points()) {
    x0 = std::min(x0, p.x());
    x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y());
    y1 = std::max(y1, p.y());
  }
  double axis_off = 0, best_off = 0;
  for (std::size_t k = 0; k < rows.total_points(); ++k) {
    const Point& p = rows.points()[k];
    const double fx = (p.x() - x0) / (x1 - x0), fy = (p.y() - y0) / (y1 - y0);
    axis_off = std::max({axis_off, std::fabs(axis->u[k] - fx), std::fabs(axis->v[k] - fy)});
    best_off = std::max({best_off, std::fabs(best->u[k] - fx), std::fabs(best->v[k] - fy)});
  }
  EXPECT_LT(axis_off, 1e-12);
  EXPECT_GT(best_off, 1e-2);  // the tilt shears the parameters
}

// No coordinate plane for closed rows (their base is an axis), nor where the best plane is
// the coordinate plane already (a flat sheet: the same parameters twice).
TEST(GeometricBasePlane, AxisPlaneOnlyWhereItDiffers) {
  Rows flat;
  for (int j = 0; j < 5; ++j) {
    for (int k = 0; k < 8; ++k) flat.push_point(Point(k, j, 2.0));
    flat.end_row();
  }
  EXPECT_TRUE(detail::base_surface_fractions(flat, false, false));
  EXPECT_FALSE(detail::base_surface_fractions(flat, false, false, detail::BasePlane::kAxis));
  Rows ring;
  for (int j = 0; j < 5; ++j) {
    for (int k = 0; k < 12; ++k)
      ring.push_point(Point(std::cos(0.5 * k), std::sin(0.5 * k), j + 0.1 * std::sin(0.5 * k)));
    ring.end_row();
  }
  EXPECT_TRUE(detail::base_surface_fractions(ring, true, false));
  EXPECT_FALSE(detail::base_surface_fractions(ring, true, false, detail::BasePlane::kAxis));
}

// The search over both planes: fewer control points than over the best plane alone on the
// tilted field (golden pairs, measured), T held at every point, no fold; the default fit
// takes it.
TEST(GeometricBasePlane, SearchTriesTheCoordinatePlane) {
  const Rows rows = clipped_scan_lines();
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  const detail::Frame fr(rows, o);
  long tried = 0;
  const auto best_only = detail::search_geometric_counted(
      fr, o, LONG_MAX, detail::kCorrectionRounds, tried, detail::BasePlane::kBest);
  const auto both = detail::search_geometric(fr, o, LONG_MAX);
  ASSERT_TRUE(best_only && both);
  const long a = static_cast<long>(best_only->surface.count_u) * best_only->surface.count_v;
  const long b = static_cast<long>(both->surface.count_u) * both->surface.count_v;
  std::printf("[ measured ] best plane %d x %d, both planes %d x %d (%s)\n",
              best_only->surface.count_u, best_only->surface.count_v, both->surface.count_u,
              both->surface.count_v, both->stop.c_str());
  EXPECT_EQ(a, 15 * 12);  // measured 2026-12-03
  EXPECT_EQ(b, 13 * 12);
  EXPECT_NE(both->stop.find("coordinate plane"), std::string::npos);
  DeviationCheck c;
  EXPECT_TRUE(fr.judge(both->surface, both->u, both->v, &c, nullptr, false).holds);
  EXPECT_TRUE(c.within);
  const FitResult f = fit_surface(rows, o);
  EXPECT_TRUE(f.report.within_tolerance);
  EXPECT_LE(test::size_of(f), b);
}

// Counts given (FitOptions::counts): where the best plane's surface misses T at the search's
// pair, the coordinate plane's is taken, and holds.
TEST(GeometricBasePlane, CountsGivenTakeTheCoordinatePlaneWhereTheBestMisses) {
  const Rows rows = clipped_scan_lines();
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  o.parametrization = Parametrization::kGeometric;
  o.counts = std::array<int, 2>{13, 12};
  const detail::Frame fr(rows, o);
  const auto best = detail::geometric_at_counts(fr, o, 13, 12);
  ASSERT_TRUE(best);
  DeviationCheck c;
  fr.judge(best->surface, best->u, best->v, &c, nullptr, false);
  EXPECT_FALSE(c.within);
  const FitResult f = fit_surface(rows, o);
  EXPECT_EQ(f.surface.count_u, 13);
  EXPECT_EQ(f.surface.count_v, 12);
  EXPECT_TRUE(f.report.within_tolerance) << f.report.stop_reason;
}

}  // namespace
}  // namespace sfit
