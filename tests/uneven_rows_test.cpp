// Rows of very different lengths on one smooth field: a long row beside short ones must not
// cost the long row's count everywhere (count_floor.h: the longest row is among the rows fitted
// alone at T, so short rows that need all their points because they are short do not read as
// noise that forces interpolation, and the geometric rule, whose smoothness term decides what
// short rows leave open, is searched; and under that rule rows that need all their points as
// curves are no proof of noise). The data of bench/adversarial.py's long_beside_short and
// zigzag_rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "count_floor.h"
#include "fit_frame.h"
#include "sfit/curve_fit.h"
#include "sfit/parametrization.h"
#include "sfit/surface_fit.h"
#include "surface_distance.h"
#include "test_support.h"

namespace sfit {
namespace {

using std::numbers::pi;

// bench/adversarial.py's field: two bumps and a gentle wave.
double field(double x, double y) {
  return 0.35 * std::exp(-((x - 0.3) * (x - 0.3) + (y + 0.2) * (y + 0.2)) / 0.18) -
         0.25 * std::exp(-((x + 0.4) * (x + 0.4) + (y - 0.35) * (y - 0.35)) / 0.09) +
         0.08 * std::sin(2.5 * x + 1.3 * y);
}

// Rows y = -1 ... 1 of the field, row j with lengths[j] points evenly spaced on x in [-1, 1].
Rows sheet(const std::vector<int>& lengths) {
  Rows rows;
  const int m = static_cast<int>(lengths.size());
  for (int j = 0; j < m; ++j) {
    const double y = -1 + 2.0 * j / (m - 1);
    for (int k = 0; k < lengths[j]; ++k) {
      const double x = -1 + 2.0 * k / (lengths[j] - 1);
      rows.push_point(Point(x, y, field(x, y)));
    }
    rows.end_row();
  }
  return rows;
}

// Closed sections of a wavy tube, section j with lengths[j] points evenly spaced in angle.
Rows tube(const std::vector<int>& lengths) {
  Rows rows;
  const int m = static_cast<int>(lengths.size());
  for (int j = 0; j < m; ++j) {
    const double z = 2.0 * j / (m - 1);
    for (int k = 0; k < lengths[j]; ++k) {
      const double a = 2 * pi * k / lengths[j];
      const double r = 1 + 0.1 * std::cos(2 * a) + 0.05 * z + 0.05 * std::sin(3 * a + z);
      rows.push_point(Point(r * std::cos(a), r * std::sin(a), z));
    }
    rows.end_row();
  }
  return rows;
}

// 31 rows: `short_length` points each, `long_length` at the rows in `long_rows`.
std::vector<int> lengths(std::vector<int> long_rows, int short_length, int long_length = 3000) {
  std::vector<int> out(31, short_length);
  for (int j : long_rows) out[j] = long_length;
  return out;
}

using test::size_of;

// T at every point at its parameters (the independent evaluator), every (stride-th) point within
// T of the surface by an independent closest-point search (T the same on every axis), fold 0.
void expect_holds(const FitResult& f, const Rows& rows, const Point& tol) {
  EXPECT_TRUE(f.report.within_tolerance);
  const Point dev = test::reference_deviation(f, rows);
  for (int a = 0; a < 3; ++a) EXPECT_LE(dev[a], tol[a] * (1 + 1e-9)) << "axis " << a;
  const std::size_t stride = std::max<std::size_t>(1, rows.total_points() / 400);
  for (std::size_t k = 0; k < rows.total_points(); k += stride)
    ASSERT_LE(test::distance_to_surface(f.surface, rows.points()[k]), tol.x() * (1 + 1e-9))
        << "point " << k;
  EXPECT_EQ(f.report.fold, 0.0);
}

struct Case {
  const char* name;
  Rows rows;
  bool closed_u;
  long at_most;  // control points: the measured pair's product with some room
};

// The default on one long row (or two) among short ones, open and closed: far fewer control
// points than points (before: 93 x 31 = 2,883 for 3,150 points on the open sheet, the paper
// rule's two stages; 13 x 29 = 377 on the tube), T at every point, no fold.
TEST(UnevenRowCount, LongRowBesideShortOnesGetsASmallSurface) {
  const Case cases[] = {
      // measured 10 x 12 = 120
      {"one long row in the middle", sheet(lengths({15}, 5)), false, 160},
      // measured 13 x 13 = 169
      {"two long rows", sheet(lengths({7, 22}, 5)), false, 220},
      // measured 10 x 12 = 120; before 64 x 31 = 1,984 for 450 points, and the report said that
      // T forces interpolation ("the rows fitted alone at T need 40 of their 40 points")
      {"one row of 300 among rows of 5", sheet(lengths({15}, 5, 300)), false, 160},
      // measured 12 x 4 = 48
      {"closed: one long section in the middle", tube(lengths({15}, 8)), true, 80},
      // measured 12 x 7 = 84
      {"closed: two long sections", tube(lengths({7, 22}, 8)), true, 120},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    FitOptions o;
    o.closed_u = c.closed_u;
    o.tolerance = relative_tolerance(c.rows, 1e-3);
    const FitResult f = fit_surface(c.rows, o);
    std::printf("[ measured ] %s (%zu points): %d x %d = %ld (%s)\n", c.name, c.rows.total_points(),
                f.surface.count_u, f.surface.count_v, size_of(f),
                std::string(to_string(f.report.parametrization)).c_str());
    expect_holds(f, c.rows, o.tolerance);
    EXPECT_LE(size_of(f), c.at_most);
    EXPECT_LT(size_of(f), static_cast<long>(c.rows.total_points()) / 2);
    EXPECT_EQ(f.report.stop_reason.find("forces interpolation"), std::string::npos);
  }
}

// Rows that zigzag across the surface (bench/adversarial.py's zigzag_rows: x runs on, y jumps
// +-0.02 from point to point): each row alone needs all its 80 points as a curve, which is no
// noise under the geometric rule (each point its own v), so that rule is still searched, below a
// quarter of the points. Before: the two stages' 80 x 24 = 1,920 for 3,200 points.
Rows zigzag_rows() {
  Rows rows;
  for (int j = 0; j < 40; ++j) {
    const double y0 = -0.95 + 1.9 * j / 39;
    for (int k = 0; k < 80; ++k) {
      const double x = -1 + 2.0 * k / 79, y = y0 + (k % 2 == 0 ? 0.02 : -0.02);
      rows.push_point(Point(x, y, field(x, y)));
    }
    rows.end_row();
  }
  return rows;
}

TEST(UnevenRowCount, ZigzagRowsAreSearchedUnderTheGeometricRule) {
  const Rows rows = zigzag_rows();
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  const FitResult f = fit_surface(rows, o);
  std::printf("[ measured ] zigzag rows (%zu points): %d x %d = %ld (%s)\n", rows.total_points(),
              f.surface.count_u, f.surface.count_v, size_of(f),
              std::string(to_string(f.report.parametrization)).c_str());
  expect_holds(f, rows, o.tolerance);
  EXPECT_EQ(f.report.parametrization, Parametrization::kGeometric);
  EXPECT_LE(size_of(f), 240);  // measured 15 x 12 = 180
}

// The same rows at 5e-6 of the diagonal under the geometric rule alone: nothing holds below
// its cap (a quarter of the points), and the two stages' surface is kept. (At 2e-5, where this
// was measured first, the coordinate plane's parameters now hold: 24 x 28 = 672, geometric.) The
// report once said "the noise forces interpolation ..., no pair searched" after 23 pairs, on data
// without noise; it now says what was searched and does not claim that T forces anything.
TEST(UnevenRowCount, ZigzagRowsBelowTheCapClaimNoNoise) {
  const Rows rows = zigzag_rows();
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 5e-6);
  o.parametrization = Parametrization::kGeometric;
  const FitResult f = fit_surface(rows, o);
  const std::string& why = f.report.stop_reason;
  std::printf("[ measured ] zigzag rows at 5e-6: %d x %d = %ld (%s), %ld pairs: %s\n",
              f.surface.count_u, f.surface.count_v, size_of(f),
              std::string(to_string(f.report.parametrization)).c_str(), f.report.pairs_tried,
              why.c_str());
  EXPECT_GT(f.report.pairs_tried, 0) << why;
  EXPECT_EQ(why.find("forces interpolation"), std::string::npos) << why;
  EXPECT_EQ(why.find("no pair searched"), std::string::npos) << why;
  EXPECT_NE(why.find("searched below 800 control points only"), std::string::npos) << why;
  expect_holds(f, rows, o.tolerance);
}

// The floor of the rows fitted alone: beside a long row, rows of 5 points that each need their 5
// control points at T (they are short) do not make it "forced", and its nu is what the long row
// needs; with only the short rows (the long one cut to 5 points too) every row needs all its
// points, as before.
TEST(UnevenRowCount, FloorFitsTheLongestRow) {
  const Rows uneven = sheet(lengths({15}, 5));
  FitOptions o;
  o.tolerance = relative_tolerance(uneven, 1e-3);
  const double roundoff = kRoundoffRelative * bounding_box(uneven).diagonal();
  const detail::CountFloor f =
      detail::count_floor(uneven, o, Parametrization::kChord, roundoff, detail::FloorPart::kRows);
  EXPECT_FALSE(f.forced);
  // The long row alone at chord length: its own count (a curve fit of 3,000 points).
  CurveFitOptions c;
  c.degree = o.degree_u;
  c.search = CountSearch::kFast;
  c.bound = o.tolerance;
  const std::vector<double> positions =
      normalized_positions(uneven[15], Parametrization::kChord, false);
  c.positions = positions;
  const int long_row = fit_curve(uneven[15], c).curve.count();
  EXPECT_GT(long_row, 5);
  EXPECT_EQ(f.nu, long_row);

  const Rows even = sheet(lengths({}, 5));
  const detail::CountFloor g =
      detail::count_floor(even, o, Parametrization::kChord, roundoff, detail::FloorPart::kRows);
  EXPECT_TRUE(g.forced);
  EXPECT_EQ(g.nu, 5);
}

}  // namespace
}  // namespace sfit
