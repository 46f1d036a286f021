// The points against the quadric through their neighbours (neighbour_noise.h), and what the
// default and the two stages make of noise far above T where rows are cut by a hole: a surface
// that holds T at every point, does not fold, and a report that says T forces interpolation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fit_driver.h"
#include "neighbour_noise.h"
#include "rows_alone.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

using test::size_of;
using test::Uniform;

double saddle(double x, double y) {
  return 4 * ((x - 0.15) * (x - 0.15) - (y - 0.11) * (y - 0.11)) +
         0.02 * std::exp(-((x - 0.22) * (x - 0.22) + (y - 0.06) * (y - 0.06)) / 0.0015);
}

// A range image of nx x ny points over [0, 0.3] x [0, 0.22] of the saddle with a bump, with
// uniform noise of +-`noise` in z and an oval hole: a row that crosses it keeps its two ends.
Rows range_image(int nx, int ny, double noise, std::uint32_t seed) {
  Uniform r(seed);
  Rows rows;
  for (int j = 0; j < ny; ++j) {
    const double y = 0.22 * j / (ny - 1);
    for (int k = 0; k < nx; ++k) {
      const double x = 0.3 * k / (nx - 1);
      const double a = std::atan2(y - 0.1, x - 0.13);
      const double e = r(-noise, noise);
      if (std::hypot(x - 0.13, y - 0.1) < 0.07 * (1 + 0.2 * std::cos(2 * a))) continue;
      rows.push_point(Point(x, y, saddle(x, y) + e));
    }
    rows.end_row();
  }
  return rows;
}

FitOptions at_t(double t) {
  FitOptions o;
  o.tolerance = Point::Constant(t);
  return o;
}

TEST(NeighbourNoise, NoiseFarAboveTForcesInterpolationWhateverTheRule) {
  const Rows rows = range_image(30, 30, 0.003, 5);
  const detail::Centring c = detail::centre_rows(rows, 1);
  std::string why;
  EXPECT_TRUE(detail::neighbours_force_interpolation(c.centred, at_t(0.0003), c.roundoff, why))
      << why;
  const detail::NeighbourNoise nn = detail::neighbour_noise(c.centred, at_t(0.0003), c.roundoff);
  EXPECT_GT(nn.points, 500);  // every point but the first and last row's ends
  EXPECT_GT(nn.median, 1.0);
  EXPECT_GT(nn.beyond, nn.points / 2);
  // Noise of half T: a smooth surface through the neighbours holds most points.
  EXPECT_FALSE(detail::neighbours_force_interpolation(c.centred, at_t(0.006), c.roundoff, why))
      << why;
}

TEST(NeighbourNoise, SmoothDataIsNotForced) {
  const Rows rows = range_image(40, 30, 0.0, 5);
  const detail::Centring c = detail::centre_rows(rows, 1);
  const detail::NeighbourNoise nn = detail::neighbour_noise(c.centred, at_t(1e-4), c.roundoff);
  EXPECT_GT(nn.points, 500);
  EXPECT_LT(nn.median, 0.1);
  std::string why;
  EXPECT_FALSE(detail::neighbours_force_interpolation(c.centred, at_t(1e-4), c.roundoff, why))
      << why;
}

// Rows that zigzag across a smooth surface (every other point 0.005 off the row's line): as
// curves they need all their points at T, which is why the rows alone do not tell for a rule
// that gives each point its own v; the points' neighbours in space do.
TEST(NeighbourNoise, ZigzagRowsOverASmoothSurfaceAreNotForced) {
  Rows rows;
  for (int j = 0; j < 30; ++j)
    for (int k = 0; k <= 60; ++k) {
      const double x = 0.3 * k / 60, y = 0.007 * j + (k % 2 ? 0.005 : 0.0);
      rows.push_point(Point(x, y, saddle(x, y)));
      if (k == 60) rows.end_row();
    }
  const detail::Centring c = detail::centre_rows(rows, 1);
  std::string why;
  EXPECT_TRUE(detail::t_forces_interpolation(c.centred, at_t(1e-5), c.roundoff, why)) << why;
  EXPECT_FALSE(detail::neighbours_force_interpolation(c.centred, at_t(1e-5), c.roundoff, why))
      << why;
}

// A smooth sheet sampled sparsely (at random along the rows) at a small T: the quadric through a
// point's neighbours misses it by more than T (its own error, the third derivatives times the
// spacing cubed), the cubic through them does not (quadric alone: the median at 3.3 T, "forced";
// the lesser of the two: 0.60 T). Noise of 5 T on the same points misses both. (The lesser of two
// misses is the cautious side of the claim: uniform noise of 3 T reads at 0.99 T and is not
// claimed; the search below the points then says what it measured.)
TEST(NeighbourNoise, SparseSmoothDataAtASmallTIsNotForced) {
  const auto sheet = [](double noise) {
    Uniform r(9);
    Rows rows;
    for (int j = 0; j < 24; ++j) {
      std::vector<double> xs(30);
      for (double& x : xs) x = r();
      std::sort(xs.begin(), xs.end());
      for (double x : xs) {
        const double y = j / 23.0;
        rows.push_point(Point(x, y, 0.3 * std::sin(5 * x) * std::cos(4 * y) + r(-noise, noise)));
      }
      rows.end_row();
    }
    return rows;
  };
  const double t = 1.5e-4;
  const detail::Centring c = detail::centre_rows(sheet(0.0), 1);
  const detail::NeighbourNoise nn = detail::neighbour_noise(c.centred, at_t(t), c.roundoff);
  EXPECT_GT(nn.points, 400);
  EXPECT_LT(nn.median, 1.0);
  std::string why;
  EXPECT_FALSE(detail::neighbours_force_interpolation(c.centred, at_t(t), c.roundoff, why)) << why;
  const detail::Centring noisy = detail::centre_rows(sheet(5 * t), 1);
  EXPECT_TRUE(detail::neighbours_force_interpolation(noisy.centred, at_t(t), noisy.roundoff, why))
      << why;
}

// Points on one line: no quadric across it, so nothing is told.
TEST(NeighbourNoise, PointsOnALineTellNothing) {
  Rows rows;
  for (int j = 0; j < 10; ++j) {
    for (int k = 0; k < 20; ++k) rows.push_point(Point(0.05 * k + 0.001 * j, 0, 0));
    rows.end_row();
  }
  const detail::Centring c = detail::centre_rows(rows, 1);
  std::string why;
  EXPECT_FALSE(detail::neighbours_force_interpolation(c.centred, at_t(1e-6), c.roundoff, why));
  EXPECT_NE(why.find("no point has neighbours"), std::string::npos) << why;
}

// Noise nine times T on a range image with a hole: the two stages' columns pass through every
// row, and rows cut by the hole put their control points elsewhere than full rows do, so a
// cubic or a quadratic across the rows doubles back between them. The fold guard lowers the
// degree across down to straight stretches, which cannot.
TEST(NeighbourNoise, TwoStagesLowerTheDegreeAcrossUntilNoFold) {
  const Rows rows = range_image(60, 45, 3.3e-4, 7);
  FitOptions o = at_t(3.7e-5);
  o.method = FitMethod::kSfit01;
  o.fold_guard = false;
  const FitResult kept = fit_surface(rows, o);
  EXPECT_GT(kept.report.fold, 1e-7 * bounding_box(rows).diagonal());  // it does fold
  o.fold_guard = true;
  const FitResult f = fit_surface(rows, o);
  EXPECT_TRUE(f.report.within_tolerance);
  EXPECT_EQ(f.report.fold, 0.0);
  EXPECT_EQ(f.surface.degree_u, 3);
  EXPECT_EQ(f.surface.degree_v, 1);
  const Point d = test::reference_deviation(f, rows);
  EXPECT_TRUE((d.array() <= o.tolerance.array() * (1 + 1e-9)).all()) << d.transpose();
}

// The default on the same data: more control points than points, and the report says why
// from the points' neighbours (the rows alone do not tell under the geometric rule).
TEST(NeighbourNoise, TheDefaultSaysTForcesInterpolationAndDoesNotFold) {
  const Rows rows = range_image(60, 45, 3.3e-4, 7);
  const FitResult f = fit_surface(rows, at_t(3.7e-5));
  EXPECT_TRUE(f.report.within_tolerance);
  EXPECT_EQ(f.report.fold, 0.0);
  EXPECT_GT(size_of(f), static_cast<long>(rows.total_points()));
  const std::string& s = f.report.stop_reason;
  EXPECT_NE(s.find("T forces interpolation"), std::string::npos) << s;
  EXPECT_NE(s.find("quadric through their neighbours"), std::string::npos) << s;
  const Point d = test::reference_deviation(f, rows);
  EXPECT_TRUE((d.array() <= 3.7e-5 * (1 + 1e-9)).all()) << d.transpose();
}

}  // namespace
}  // namespace sfit
