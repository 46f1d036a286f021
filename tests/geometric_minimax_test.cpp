// The geometric rule's minimax where no pair held by least squares (geometric_search.cpp,
// minimax_rescue(); docs/method.md 7.9): a range image with a hole and noise near T, where
// least squares follows the noise's peaks past T at every pair while a smooth surface within
// T of every point exists (the noise-free one is within 0.9 T).
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstdio>

#include "fit_frame.h"
#include "geometric_search.h"
#include "search_frame.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

// nx x ny samples of a saddle with a bump, 0.3 x 0.22 across, a round hole of radius `hole` in
// the middle (a row crossing it keeps both ends), heights plus uniform noise of `level` times
// 1e-3 of the diagonal.
Rows noisy_range_image(int nx, int ny, double level, unsigned seed, double hole) {
  test::Uniform r(seed);
  Rows rows;
  const double diag = std::sqrt(0.3 * 0.3 + 0.22 * 0.22 + 0.08 * 0.08);
  for (int j = 0; j < ny; ++j) {
    const double y = 0.22 * j / (ny - 1);
    for (int i = 0; i < nx; ++i) {
      const double x = 0.3 * i / (nx - 1);
      if (std::hypot(x - 0.13, y - 0.1) < hole) continue;
      const double z =
          4 * ((x - 0.15) * (x - 0.15) - (y - 0.11) * (y - 0.11)) +
          0.02 * std::exp(-((x - 0.22) * (x - 0.22) + (y - 0.06) * (y - 0.06)) / 0.0015);
      rows.push_point(Point(x, y, z + level * 1e-3 * diag * (2 * r() - 1)));
    }
    rows.end_row();
  }
  return rows;
}

// Every point of `g` within T (judged with the rule's guards), the surface near the data and
// unfolded; the check, for more.
DeviationCheck expect_held_near_unfolded(const detail::Frame& fr, const detail::GeometricFit& g) {
  DeviationCheck c;
  EXPECT_TRUE(fr.judge(g.surface, g.u, g.v, &c, nullptr, false).holds);
  EXPECT_TRUE(c.within);
  EXPECT_TRUE(detail::stays_near_where_covered(g.surface, g.u, g.v, fr.centred_box));
  EXPECT_EQ(detail::geometric_fold(g.surface), 0.0);
  return c;
}

// 1,548 points with noise of 0.9 T: least squares over the best plane's parameters holds T
// only at 196 control points (in effect following the noise); minimax at the nearest pair
// holds at 190. (At noise 0.95 T and seed 1 minimax once gave 19 x 19 where least squares
// needed 814, but that surface rose 0.11, 0.3 of the diagonal, out of the box over the hole:
// the guard of the spans between spans with data now refuses it; see below.)
TEST(GeometricMinimax, NoiseNearTHoldsBelowLeastSquaresCount) {
  const Rows rows = noisy_range_image(50, 37, 0.9, 2, 0.06);
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  const detail::Frame fr(rows, o);
  const long points = static_cast<long>(rows.total_points());
  ASSERT_EQ(points, 1548);
  // Least squares alone (no minimax below a bound of 0).
  const auto l2 = detail::search_geometric(fr, o, points, detail::kCorrectionRounds, nullptr, 0);
  ASSERT_TRUE(l2);
  const long nl2 = static_cast<long>(l2->surface.count_u) * l2->surface.count_v;
  EXPECT_EQ(l2->norm, FitNorm::kL2);
  const auto g = detail::search_geometric(fr, o, points);
  ASSERT_TRUE(g);
  const long n = static_cast<long>(g->surface.count_u) * g->surface.count_v;
  std::printf("[ measured ] %ld points: least squares %d x %d = %ld, minimax %d x %d = %ld\n",
              points, l2->surface.count_u, l2->surface.count_v, nl2, g->surface.count_u,
              g->surface.count_v, n);
  EXPECT_EQ(nl2, 196);
  EXPECT_EQ(g->norm, FitNorm::kLinf);
  EXPECT_EQ(n, 190);
  EXPECT_LE(expect_held_near_unfolded(fr, *g).max_deviation.z(), o.tolerance.z());
  // Least squares asked for (norm l2): no minimax, the least-squares count.
  FitOptions only_l2 = o;
  only_l2.norm = FitNorm::kL2;
  const auto h = detail::search_geometric(fr, only_l2, points);
  ASSERT_TRUE(h);
  EXPECT_EQ(static_cast<long>(h->surface.count_u) * h->surface.count_v, nl2);
}

// At noise 0.95 T (seed 1) the minimax at the nearest pair, 19 x 19, holds every point but
// has no smoothness term: over the hole, where no point holds it, it rose 0.11 (0.3 of the
// diagonal) above the data's box. The hole's spans lie between spans with data, so the
// guard holds them within a tenth of the diagonal of the box as it does the spans with data,
// and the search keeps least squares' 22 x 37 instead.
TEST(GeometricMinimax, ASurfaceThatRisesOverAHoleIsRefused) {
  const Rows rows = noisy_range_image(50, 37, 0.95, 1, 0.06);
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  const detail::Frame fr(rows, o);
  const long points = static_cast<long>(rows.total_points());
  const auto g = detail::search_geometric(fr, o, points);
  ASSERT_TRUE(g);
  EXPECT_TRUE(detail::stays_near_where_covered(g->surface, g->u, g->v, fr.centred_box));
  EXPECT_EQ(g->norm, FitNorm::kL2);
  EXPECT_EQ(static_cast<long>(g->surface.count_u) * g->surface.count_v, 814);
  const FitResult f = fit_surface(rows, o);
  EXPECT_LT(f.report.box_excursion, 0.1 * bounding_box(rows).diagonal());
}

// At noise 0.95 T, seed 4, no pair that least squares solved misses T by at most 1.25x (the
// nearest within the LP's size, 19 x 19, by more): minimax there was not tried and the search
// kept least squares' 20 x 32. A surface within T at a pair has least squares within 2 T (the
// projector's max-norm is at least 1), so the pair least squares missed least, if within 2 T,
// is tried too: 19 x 19 holds by minimax, near the data and unfolded.
TEST(GeometricMinimax, ThePairMissedLeastIsTriedWhereNoneIsWithinReach) {
  const Rows rows = noisy_range_image(50, 37, 0.95, 4, 0.06);
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  const detail::Frame fr(rows, o);
  const long points = static_cast<long>(rows.total_points());
  const auto l2 = detail::search_geometric(fr, o, points, detail::kCorrectionRounds, nullptr, 0);
  ASSERT_TRUE(l2);
  EXPECT_EQ(static_cast<long>(l2->surface.count_u) * l2->surface.count_v, 640);
  const auto g = detail::search_geometric(fr, o, points);
  ASSERT_TRUE(g);
  EXPECT_EQ(g->norm, FitNorm::kLinf);
  EXPECT_EQ(g->surface.count_u, 19);
  EXPECT_EQ(g->surface.count_v, 19);
  expect_held_near_unfolded(fr, *g);
  const FitResult f = fit_surface(rows, o);
  EXPECT_TRUE(f.report.within_tolerance);
  EXPECT_EQ(test::size_of(f), 361);
  const Point dev = test::reference_deviation(f, rows);
  for (int a = 0; a < 3; ++a) EXPECT_LE(dev[a], o.tolerance[a] * (1 + 1e-9)) << a;
}

}  // namespace
}  // namespace sfit
