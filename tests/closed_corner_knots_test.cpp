// Corner knots on closed rows (docs/method.md, "Corner knots"): the corners of a closed row
// (its windows wrapping around its start), the default fit on a generated duct of
// rounded-rectangle sections started at random points (fewer control points than points and
// than uniform knots, every point within T by an independent evaluation, no fold, the surface
// closed with a crease at the seam corner: first and last control-point columns equal), and
// smooth closed rows unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "corner_rows.h"
#include "sfit/fold_check.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A rounded rectangle w x h (corner radius r, 0: sharp) at height z, turned by `turn`, sampled
// at n points spaced unevenly (steps 0.4 ... 1.6 of the mean) from a random start.
std::vector<Point> rounded_section(double w, double h, double r, double z, double turn, int n,
                                   unsigned seed) {
  std::vector<Point> dense;
  const double cx[] = {w / 2 - r, -w / 2 + r, -w / 2 + r, w / 2 - r};
  const double cy[] = {h / 2 - r, h / 2 - r, -h / 2 + r, -h / 2 + r};
  for (int k = 0; k < 4; ++k) {
    for (int i = 0; i <= 100; ++i) {
      const double a = kPi / 2 * (k + i / 100.0);
      dense.push_back(Point(cx[k] + r * std::cos(a), cy[k] + r * std::sin(a), z));
    }
  }
  dense.push_back(dense.front());
  std::vector<double> s(dense.size(), 0.0);
  for (std::size_t i = 1; i < dense.size(); ++i) s[i] = s[i - 1] + (dense[i] - dense[i - 1]).norm();
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> step(0.4, 1.6), start(0, 1);
  std::vector<double> t{0};
  for (int i = 1; i <= n; ++i) t.push_back(t.back() + step(gen));
  const double from = start(gen);
  std::vector<Point> out;
  for (int i = 0; i < n; ++i) {
    double at = (t[static_cast<std::size_t>(i)] / t.back() + from) * s.back();
    at -= s.back() * std::floor(at / s.back());
    const std::size_t k = std::min<std::size_t>(
        static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), at) - s.begin()),
        s.size() - 1);
    const double f = std::clamp((at - s[k - 1]) / (s[k] - s[k - 1]), 0.0, 1.0);
    const Point p = (1 - f) * dense[k - 1] + f * dense[k];
    const double c = std::cos(turn), sn = std::sin(turn);
    out.push_back(Point(c * p.x() - sn * p.y(), sn * p.x() + c * p.y(), z));
  }
  return out;
}

// A duct along z: sections widening, their corners sharp at the start and rounded to 0.25 at
// the end, turning by 0.3 rad; 120 ... 300 points each.
Rows duct(int count) {
  Rows rows;
  std::mt19937 gen(11);
  std::uniform_int_distribution<int> points(120, 300);
  for (int j = 0; j < count; ++j) {
    const double s = double(j) / (count - 1);
    rows.add_row(rounded_section(2 + s, 1 + 0.3 * std::sin(3 * s), 0.25 * s, 6 * s, 0.3 * s,
                                 points(gen), 200 + static_cast<unsigned>(j)));
  }
  return rows;
}

long count(const FitResult& r) {
  return long(r.report.count_u) * r.report.count_v;
}

TEST(ClosedCornerKnots, FindsTheCornersOfAClosedRowAcrossItsStart) {
  const Point tol = Point::Constant(0.003);
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    const auto row = rounded_section(2, 1, 0, 0, 0, 200, seed);
    EXPECT_EQ(detail::row_corners(row, tol, true).size(), 4u) << seed;
    EXPECT_EQ(detail::row_corners(rounded_section(2, 1, 0.1, 0, 0, 200, seed), tol, true).size(),
              4u)
        << seed;
  }
  // A circle: none.
  std::vector<Point> circle;
  for (int i = 0; i < 300; ++i)
    circle.push_back(Point(std::cos(2 * kPi * i / 300), std::sin(2 * kPi * i / 300), 0));
  EXPECT_TRUE(detail::row_corners(circle, tol, true).empty());
}

TEST(ClosedCornerKnots, CorneredDuctFitsBelowItsPointsAndStaysClosed) {
  const Rows rows = duct(16);
  FitOptions o;
  o.closed_u = true;
  o.tolerance = relative_tolerance(rows, 1e-3);
  const FitResult r = fit_surface(rows, o);
  FitOptions uo = o;
  uo.knots = KnotRule::kUniform;  // the default before closed rows had corner knots
  const FitResult u = fit_surface(rows, uo);
  std::printf("[ measure  ] duct 1e-3, %zu points: %d x %d = %ld (uniform knots %d x %d = %ld)\n",
              rows.total_points(), r.report.count_u, r.report.count_v, count(r), u.report.count_u,
              u.report.count_v, count(u));
  EXPECT_EQ(r.report.knots, KnotRule::kCorners);
  EXPECT_LT(count(r), static_cast<long>(rows.total_points()));
  EXPECT_LT(count(r), count(u));
  EXPECT_TRUE(r.report.within_tolerance);
  const Point d = test::reference_deviation(r, rows);
  for (int a = 0; a < 3; ++a) EXPECT_LE(d[a], o.tolerance[a]);
  EXPECT_EQ(r.report.fold, 0.0);
  // Closed: on clamped u knots whose first and last control-point columns are equal (the seam
  // a crease, a degree-fold knot inside: the ends have degree + 1), the report's closed flag
  // true, and the surface meets itself at the seam.
  EXPECT_TRUE(r.report.closed_u);
  ASSERT_FALSE(r.surface.periodic_u);
  for (int j = 0; j < r.surface.count_v; ++j)
    EXPECT_EQ(r.surface.at(0, j), r.surface.at(r.surface.count_u - 1, j)) << j;
  const double end = r.surface.u_end();
  for (double v : {0.0, 0.3, 0.7, 1.0}) {
    const double at = v * r.surface.v_end();
    EXPECT_LE((r.surface.evaluate(0, at) - r.surface.evaluate(end, at)).norm(), 1e-12) << v;
  }
  // Each row starts (u = 0) at its seam corner, which the report's seams name: after the
  // point they name (or at it) the row's smallest u.
  ASSERT_EQ(r.report.seams.size(), rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const RowSeam& seam = r.report.seams[j];
    const double* u = r.u.data() + rows.offsets()[j];
    const std::size_t n = rows[j].size(), k = source_index(seam, n, seam.offset > 0 ? 1 : 0);
    EXPECT_EQ(u[k], *std::min_element(u, u + n)) << j;
    EXPECT_LT(u[k], 0.05) << j;
  }
}

TEST(ClosedCornerKnots, SmoothClosedRowsAreUnchanged) {
  const Rows rows = test::sample_rows(
      [](double s, double t) {
        const double a = 2 * kPi * s;
        return Point((1 + 0.3 * t) * std::cos(a), (0.6 + 0.1 * std::sin(3 * t)) * std::sin(a),
                     2 * t);
      },
      std::vector<int>(14, 80), true);
  FitOptions o;
  o.closed_u = true;
  o.tolerance = relative_tolerance(rows, 1e-3);
  const FitResult r = fit_surface(rows, o);
  FitOptions uo = o;
  uo.knots = KnotRule::kUniform;
  const FitResult u = fit_surface(rows, uo);
  EXPECT_EQ(r.report.knots, KnotRule::kUniform);
  test::expect_same_surface(r, u);
}

}  // namespace
}  // namespace sfit
