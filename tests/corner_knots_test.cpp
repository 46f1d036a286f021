// Corner knots (docs/method.md, "Corner knots"): the corners found on a row (sharp and
// rounded; noise within T is none), the default fit on generated cornered stations (far fewer
// control points than before, every point within T by an independent evaluation, no fold),
// rows without corners unchanged, and the JSON round trip of the corner knots.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "corner_rows.h"
#include "sfit/fold_check.h"
#include "sfit/io/report_json.h"
#include "sfit/io/surface_json.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

// A polyline a -> b -> c -> d with the corners at b and c rounded by radius rb, rc (0: sharp),
// sampled at n points spaced unevenly (steps 0.4 ... 1.6 of the mean, fixed by `seed`), at x.
std::vector<Point> section(double x, double rb, double rc, int n, unsigned seed, double noise,
                           double grow = 0) {
  const Point a(x, 0, 0), b(x, 4 - 2 * grow, 0.6), c(x, 4.4 - 2 * grow, 3.5 + 2 * grow),
      d(x, 0.2, 3.8 + 2 * grow);
  // The path as dense samples: each corner replaced by a circular-ish arc (a quadratic Bezier
  // between the points at distance r from the corner along both legs).
  std::vector<Point> dense;
  auto leg = [&](const Point& p, const Point& q, int m) {
    for (int i = 0; i < m; ++i) dense.push_back(p + (q - p) * (double(i) / m));
  };
  auto round = [&](const Point& p, const Point& k, const Point& q, double r) {
    const Point s = k + (p - k).normalized() * r, e = k + (q - k).normalized() * r;
    for (int i = 0; i < 200; ++i) {
      const double t = i / 200.0;
      dense.push_back((1 - t) * (1 - t) * s + 2 * t * (1 - t) * k + t * t * e);
    }
    return e;
  };
  const Point b0 = b + (a - b).normalized() * rb;
  leg(a, b0, 2000);
  const Point b1 = round(a, b, c, rb);
  const Point c0 = c + (b - c).normalized() * rc;
  leg(b1, c0, 2000);
  const Point c1 = round(b, c, d, rc);
  leg(c1, d, 2000);
  dense.push_back(d);
  std::vector<double> s(dense.size(), 0.0);
  for (std::size_t i = 1; i < dense.size(); ++i) s[i] = s[i - 1] + (dense[i] - dense[i - 1]).norm();
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> step(0.4, 1.6), jitter(-noise, noise);
  std::vector<double> t{0};
  for (int i = 1; i < n; ++i) t.push_back(t.back() + step(gen));
  std::vector<Point> out;
  std::size_t k = 0;
  for (double ti : t) {
    const double at = ti / t.back() * s.back();
    while (k + 2 < s.size() && s[k + 1] < at) ++k;
    const double f = s[k + 1] > s[k] ? std::clamp((at - s[k]) / (s[k + 1] - s[k]), 0.0, 1.0) : 0;
    out.push_back((1 - f) * dense[k] + f * dense[k + 1] + Point(0, jitter(gen), jitter(gen)));
  }
  return out;
}

// Stations along x: the first corner sharp aft and rounded (up to 0.3) forward, the second
// sharp throughout; the bottom narrows and the side grows, so the corners' chord fractions move
// from 0.36 and 0.63 to 0.16 and 0.63; 80 ... 200 points a row, unevenly spaced.
Rows stations(int count) {
  Rows rows;
  std::mt19937 gen(5);
  std::uniform_int_distribution<int> points(80, 200);
  for (int j = 0; j < count; ++j) {
    const double s = double(j) / (count - 1);
    rows.add_row(section(20 * s, 0.5 * std::max(0.0, s - 0.4), 0, points(gen), 100 + j, 0, s));
  }
  return rows;
}

long count(const FitResult& r) {
  return long(r.report.count_u) * r.report.count_v;
}

TEST(CornerKnots, FindsSharpAndRoundedCornersButNotNoiseWithinT) {
  const Point tol = Point::Constant(0.005);
  const auto sharp = detail::row_corners(section(0, 0, 0, 300, 1, 0), tol);
  ASSERT_EQ(sharp.size(), 2u);
  // The corners' chord fractions: 4.04 / 11.13 and 6.98 / 11.13 of the way along.
  EXPECT_NEAR(sharp[0].fraction, 0.363, 0.01);
  EXPECT_NEAR(sharp[1].fraction, 0.627, 0.01);
  EXPECT_GT(sharp[0].turn, 1.2);  // 81 degrees, within the window's sampling
  const auto rounded = detail::row_corners(section(0, 0.3, 0.3, 300, 2, 0), tol);
  ASSERT_EQ(rounded.size(), 2u);
  EXPECT_NEAR(rounded[0].fraction, sharp[0].fraction, 0.02);
  // A straight row with noise of half T: no corner.
  std::vector<Point> line;
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> n(-0.0025, 0.0025);
  for (int i = 0; i < 400; ++i) line.push_back(Point(0, 0.01 * i, n(gen)));
  EXPECT_TRUE(detail::row_corners(line, tol).empty());
  // The noisy cornered row keeps its two corners.
  EXPECT_EQ(detail::row_corners(section(0, 0, 0, 300, 1, 0.0025), tol).size(), 2u);
}

TEST(CornerKnots, CorneredStationsNeedFewerThanHalfOfBefore) {
  const Rows rows = stations(24);
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  const FitResult r = fit_surface(rows, o);
  // Before corner knots the default needed 83 x 14 = 1,162 (the same rows, measured
  // 2026-12-03 with the build before this change); with them 19 x 23 = 437.
  constexpr long kBefore = 1162;
  std::printf("[ measure  ] cornered stations 1e-3: %d x %d = %ld (before %ld)\n", r.report.count_u,
              r.report.count_v, count(r), kBefore);
  EXPECT_EQ(r.report.knots, KnotRule::kCorners);
  EXPECT_EQ(r.report.parametrization, Parametrization::kChord);
  EXPECT_LE(count(r), kBefore / 2);
  EXPECT_TRUE(r.report.within_tolerance);
  const Point d = test::reference_deviation(r, rows);
  for (int a = 0; a < 3; ++a) EXPECT_LE(d[a], o.tolerance[a]);
  EXPECT_EQ(r.report.fold, 0.0);
  EXPECT_EQ(fold_measure(r.surface, r.v), 0.0);
  // The u knots: a degree-fold knot at each of the two corners.
  std::vector<double> b;
  std::vector<int> m;
  r.surface.knots_u.breaks(b, m);
  int creases = 0;
  for (int x : m) creases += x == r.surface.degree_u;
  EXPECT_EQ(creases, 2);  // the two corners (the ends have degree + 1)
}

TEST(CornerKnots, RowsWithoutCornersAreUnchanged) {
  const Rows rows = test::sample_rows(
      [](double s, double t) { return Point(s, t, 0.2 * std::sin(3 * s + t) * std::cos(2 * t)); },
      std::vector<int>(20, 60));
  for (std::size_t j = 0; j < rows.size(); ++j)
    EXPECT_TRUE(detail::row_corners(rows[j], relative_tolerance(rows, 1e-3)).empty());
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  const FitResult r = fit_surface(rows, o);
  EXPECT_EQ(r.report.knots, KnotRule::kUniform);
  EXPECT_TRUE(r.surface.knots_u.uniform());
  EXPECT_TRUE(r.surface.knots_v.uniform());
}

TEST(CornerKnots, KnotsAndReportSurviveTheJsonRoundTrip) {
  const Rows rows = stations(16);
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  const FitResult r = fit_surface(rows, o);
  ASSERT_EQ(r.report.knots, KnotRule::kCorners);
  const Surface back = io::surface_from_json_text(io::surface_to_json_text(r.surface), "corners");
  EXPECT_EQ(back.knots_u, r.surface.knots_u);
  EXPECT_EQ(back.knots_v, r.surface.knots_v);
  EXPECT_EQ(back.control, r.surface.control);
  const std::string text = io::report_to_json_text(r.report);
  EXPECT_NE(text.find("\"knots\": \"corners\""), std::string::npos);
  const FitReport report = io::report_from_json_text(text, "report");
  EXPECT_EQ(report.knots, KnotRule::kCorners);
  EXPECT_EQ(report.parametrization, Parametrization::kChord);
  EXPECT_EQ(io::report_to_json_text(report), text);
}

}  // namespace
}  // namespace sfit
