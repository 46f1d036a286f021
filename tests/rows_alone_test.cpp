// What the rows need alone at T (rows_alone.h): the test that says when T forces (near)
// interpolation, on noise above T, on smooth rows, and on short rows beside a long one.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "below_points.h"
#include "fit_driver.h"
#include "rows_alone.h"
#include "search_frame.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

using test::Uniform;

using test::at;
using test::size_of;

// Ragged rows (10 ... 20 points) whose noise is ten times T: every row needs all its points,
// the two stages interpolate (nu = the longest row, one control point per row across: more
// than the points), and the report says that T forces it.
TEST(RowsAlone, NoiseAboveTForcesInterpolationAndTheReportSaysSo) {
  Uniform r(3);
  Rows rows;
  for (int j = 0; j < 12; ++j) {
    const int n = 10 + (j * 7) % 11;
    for (int k = 0; k < n; ++k) {
      const double x = static_cast<double>(k) / (n - 1);
      rows.push_point(Point(x, 0.1 * j, 0.2 * (r() - 0.5)));
    }
    rows.end_row();
  }
  FitOptions o;
  o.tolerance = Point::Constant(0.01);  // the noise: up to 0.1
  std::string why;
  const detail::Centring c = detail::centre_rows(rows, 1);
  EXPECT_TRUE(detail::t_forces_interpolation(c.centred, o, c.roundoff, why)) << why;
  const FitResult f = fit_surface(rows, o);
  EXPECT_TRUE(f.report.within_tolerance);
  EXPECT_GT(size_of(f), static_cast<long>(rows.total_points()));
  EXPECT_NE(f.report.stop_reason.find("T forces interpolation"), std::string::npos)
      << f.report.stop_reason;
}

// Rows with sharp corners (keel, chine, side, deck) at a tight T: on uniform knots each row
// alone needs about all its points (a smooth curve follows a corner only with tiny spans), so
// they once read as "T forces interpolation" (hull stations: 2,010 of 2,105 points). Fitted
// in pieces between their corners they need a few control points a leg.
TEST(RowsAlone, CornersAreNotNoise) {
  Rows rows;
  for (int j = 0; j < 10; ++j) {
    const double x = j, b = 4 + 0.1 * j;
    const Point c[] = {Point(x, 0, 0), Point(x, b, 0.8), Point(x, b + 0.3, 3.5),
                       Point(x, 0.2, 3.8)};
    const double len[] = {(c[1] - c[0]).norm(), (c[2] - c[1]).norm(), (c[3] - c[2]).norm()};
    const double total = len[0] + len[1] + len[2];
    for (int k = 0; k < 200; ++k) {
      double a = total * k / 199;
      int leg = 0;
      while (leg < 2 && a > len[leg]) a -= len[leg++];
      rows.push_point(c[leg] + (c[leg + 1] - c[leg]) * std::min(1.0, a / len[leg]));
    }
    rows.end_row();
  }
  const detail::Centring c = detail::centre_rows(rows, 1);
  std::string why;
  EXPECT_FALSE(detail::t_forces_interpolation(c.centred, at(rows, 1e-5), c.roundoff, why)) << why;
  // The same rows with noise ten times T are forced.
  Uniform r(5);
  Rows noisy;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (const Point& p : rows[j]) noisy.push_point(p + Point(0, 0, 1e-3 * (r() - 0.5)));
    noisy.end_row();
  }
  const detail::Centring n = detail::centre_rows(noisy, 1);
  EXPECT_TRUE(detail::t_forces_interpolation(n.centred, at(noisy, 1e-5), n.roundoff, why)) << why;
}

// Smooth rows need far fewer control points than points: T forces nothing.
TEST(RowsAlone, SmoothRowsAreNotForced) {
  Rows rows;
  for (int j = 0; j < 10; ++j) {
    for (int k = 0; k < 50; ++k) {
      const double x = k / 49.0, y = 0.1 * j;
      rows.push_point(Point(x, y, std::sin(3 * x) * std::cos(2 * y)));
    }
    rows.end_row();
  }
  const detail::Centring c = detail::centre_rows(rows, 1);
  std::string why;
  EXPECT_FALSE(detail::t_forces_interpolation(c.centred, at(rows, 1e-3), c.roundoff, why)) << why;
}

// Rows of a few points more than the degree need all their points at any T: 30 rows of 5
// points beside one smooth row of 300 once read as "T forces interpolation" ("the rows fitted
// alone at T need 40 of their 40 points": the 8 rows the test fits were all short). The
// longest row is fitted too, and it needs few of its points.
TEST(RowsAlone, ShortRowsBesideALongOneDoNotForceInterpolation) {
  Rows rows;
  for (int j = 0; j < 31; ++j) {
    const int n = j == 15 ? 300 : 5;
    for (int k = 0; k < n; ++k) {
      const double x = -1 + 2.0 * k / (n - 1), y = -1 + 2.0 * j / 30;
      rows.push_point(Point(x, y, 0.3 * std::sin(2 * x + y) + 0.2 * std::cos(3 * y)));
    }
    rows.end_row();
  }
  const detail::Centring c = detail::centre_rows(rows, 1);
  std::string why;
  EXPECT_FALSE(detail::t_forces_interpolation(c.centred, at(rows, 1e-3), c.roundoff, why)) << why;
  // The 8 spread rows (40 points) and the long row (300 points).
  EXPECT_NE(why.find("of their 340 points"), std::string::npos) << why;
}

}  // namespace
}  // namespace sfit
