// The corners of rows (corner_rows.h): a corner that falls between two samples is placed
// between them, a kink weaker than the corner angle is found while a smooth bend of the same
// turning is not, corners that move along the rows faster than the mean's reach are followed
// from row to row; and the default fit on generated hard-chine hull stations (gaps at
// corners, weak knuckles, a narrowing bow) below the points at 1e-3 and 1e-4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "corner_rows.h"
#include "sfit/fold_check.h"
#include "sfit/surface_fit.h"
#include "shapes.h"
#include "test_support.h"

namespace sfit {
namespace {

// A row along the polyline `corner` (in the plane x = 0), `n` points evenly spaced by arc
// length, without the samples whose arc length lies in (gap_from, gap_to).
std::vector<Point> polyline_row(const std::vector<Point>& corner, int n, double gap_from = -1,
                                double gap_to = -1) {
  std::vector<double> arc{0};
  for (std::size_t k = 1; k < corner.size(); ++k)
    arc.push_back(arc.back() + (corner[k] - corner[k - 1]).norm());
  std::vector<Point> out;
  for (int i = 0; i < n; ++i) {
    const double a = arc.back() * i / (n - 1);
    if (a > gap_from && a < gap_to) continue;
    std::size_t k = 1;
    while (k + 1 < arc.size() && arc[k] < a) ++k;
    const double f = (a - arc[k - 1]) / (arc[k] - arc[k - 1]);
    out.push_back((1 - f) * corner[k - 1] + f * corner[k]);
  }
  return out;
}

// The fraction of the row's chord length at which the row passes nearest `p`.
double chord_fraction_at(const std::vector<Point>& row, const Point& p) {
  std::vector<double> s{0};
  for (std::size_t i = 1; i < row.size(); ++i) s.push_back(s.back() + (row[i] - row[i - 1]).norm());
  double best = 1e300, at = 0;
  for (std::size_t i = 1; i < row.size(); ++i) {
    const Point e = row[i] - row[i - 1];
    const double t = std::clamp((p - row[i - 1]).dot(e) / e.dot(e), 0.0, 1.0);
    const double d = (row[i - 1] + t * e - p).norm();
    if (d < best) {
      best = d;
      at = s[i - 1] + t * (s[i] - s[i - 1]);
    }
  }
  return at / s.back();
}

TEST(CornerRows, ACornerBetweenTwoSamplesIsPlacedBetweenThem) {
  // A right angle at (0, 4, 0) on a row 8 long; the samples within 0.25 of it are missing, so
  // the nearest samples are 0.25 before and after it along the row.
  const Point c(0, 4, 0);
  const std::vector<Point> row = polyline_row({Point(0, 0, 0), c, Point(0, 4, 4)}, 161, 3.75, 4.25);
  const auto found = detail::row_corners(row, Point::Constant(0.002));
  ASSERT_EQ(found.size(), 1u);
  // Between the two samples, where the row's chord (cutting the corner) passes nearest it.
  const double want = chord_fraction_at(row, c);
  EXPECT_NEAR(found[0].fraction, want, 0.002);
  // The samples either side are 0.25 from the corner: one of them would be 0.03 off.
  EXPECT_GT(std::abs(found[0].fraction - (want + 0.03)), 0.02);
}

TEST(CornerRows, AKinkWeakerThanTheCornerAngleIsFoundButNotASmoothBend) {
  const Point tol = Point::Constant(0.002);
  // A kink of 25 degrees (below the 34 of a corner) in a row 10 long.
  const double a = 25 * 3.141592653589793 / 180;
  const std::vector<Point> kink = polyline_row(
      {Point(0, 0, 0), Point(0, 5, 0), Point(0, 5 + 5 * std::cos(a), 5 * std::sin(a))}, 400);
  const auto k = detail::row_corners(kink, tol);
  ASSERT_EQ(k.size(), 1u);
  EXPECT_NEAR(k[0].fraction, 0.5, 0.01);
  // The same turning spread over an arc of 2 (a fifth of the row): no corner.
  std::vector<Point> bend;
  for (int i = 0; i < 400; ++i) {
    const double s = 10.0 * i / 399;
    if (s < 4) {
      bend.push_back(Point(0, s, 0));
    } else if (s < 6) {
      const double r = 2 / a, th = (s - 4) / r;
      bend.push_back(Point(0, 4 + r * std::sin(th), r * (1 - std::cos(th))));
    } else {
      const double r = 2 / a;
      const Point e(0, 4 + r * std::sin(a), r * (1 - std::cos(a)));
      bend.push_back(e + (s - 6) * Point(0, std::cos(a), std::sin(a)));
    }
  }
  EXPECT_TRUE(detail::row_corners(bend, tol).empty());
}

TEST(CornerRows, CornersMovingAlongTheRowsAreFollowedFromRowToRow) {
  // 12 rows whose one corner moves from 0.6 of the row to 0.3, by 0.03 a row: the last rows'
  // corners are farther than the matching's reach (0.12) from the mean (0.46).
  std::vector<std::vector<detail::RowCorner>> corners;
  for (int j = 0; j < 12; ++j) corners.push_back({{0.6 - 0.027 * j, 1.2}});
  const detail::MatchedCorners m = detail::match_corners(corners);
  ASSERT_EQ(m.common.size(), 1u);
  for (int j = 0; j < 12; ++j) EXPECT_DOUBLE_EQ(m.fraction[j][0], corners[j][0].fraction) << j;
}

TEST(CornerRows, AWeakKinkBesideACornerDoesNotTakeItsPlace) {
  // A third of the rows show a weak chine (20 degrees) at 0.34 beside the knuckle (55) at
  // 0.384; the others show the knuckle only, and all a deck corner at 0.62. Towards the bow
  // the corners move down, so the knuckles' mean (0.356) lies nearer the chine than the
  // knuckle: the sharper corner is matched first.
  std::vector<std::vector<detail::RowCorner>> corners;
  for (int j = 0; j < 12; ++j) {
    const double shift = j >= 9 ? -0.045 * (j - 8) : 0.0;  // the bow: the corners move down
    if (j % 3 == 0)
      corners.push_back({{0.34 + shift, 0.35}, {0.384 + shift, 0.96}, {0.62, 1.5}});
    else
      corners.push_back({{0.384 + shift, 0.96}, {0.62, 1.5}});
  }
  const detail::MatchedCorners m = detail::match_corners(corners);
  ASSERT_EQ(m.common.size(), 2u);
  for (int j = 0; j < 12; ++j) {
    const double shift = j >= 9 ? -0.045 * (j - 8) : 0.0;
    EXPECT_DOUBLE_EQ(m.fraction[j][0], 0.384 + shift) << j;
    EXPECT_DOUBLE_EQ(m.fraction[j][1], 0.62) << j;
  }
}

TEST(CornerRows, HullStationsFitFarBelowTheirPoints) {
  // Three hulls (seeds), at 1e-3 and 1e-4 of the diagonal: below half their points. Before
  // corner knots followed gaps, kinks and a moving bow the default gave 1,368, 3,504 and
  // 2,592 control points at 1e-4 (seed 2 above half its 6,448 points); uniform knots need
  // about every point of a station at a sharp corner.
  for (const std::uint32_t seed : {1u, 2u, 3u}) {
    const Rows rows = test::hull_stations(24, seed);
    for (const double rel : {1e-3, 1e-4}) {
      FitOptions o;
      o.tolerance = relative_tolerance(rows, rel);
      const FitResult r = fit_surface(rows, o);
      const long points = static_cast<long>(rows.total_points());
      const long cps = long(r.report.count_u) * r.report.count_v;
      std::printf("[ measure  ] hull seed %u at %g: %d x %d = %ld for %ld points (%s)\n", seed, rel,
                  r.report.count_u, r.report.count_v, cps, points,
                  to_string(r.report.knots).data());
      EXPECT_LT(cps, points / 2) << seed << " " << rel;
      EXPECT_TRUE(r.report.within_tolerance);
      const Point d = test::reference_deviation(r, rows);
      for (int a = 0; a < 3; ++a) EXPECT_LE(d[a], o.tolerance[a]) << seed << " " << rel;
      EXPECT_EQ(r.report.fold, 0.0);
      EXPECT_EQ(r.report.stop_reason.find("T forces"), std::string::npos) << r.report.stop_reason;
      if (r.report.knots == KnotRule::kCorners) {  // the report says what made the surface
        EXPECT_EQ(r.report.stop_reason.rfind("corner knots: ", 0), 0u) << r.report.stop_reason;
      }
    }
  }
}

}  // namespace
}  // namespace sfit
