// Jumps spread over the data (neighbour_noise.h's jump_spread() and
// jumps_force_interpolation()): steps and spikes far beyond T in at least half of the rows and
// across half a row's length need knot lines about everywhere, which the report then says;
// a step along one place of every row, rows far apart over a curved surface and noise within T
// do not.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fit_driver.h"
#include "neighbour_noise.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

using test::Uniform;

FitOptions at_t(double t) {
  FitOptions o;
  o.tolerance = Point::Constant(t);
  return o;
}

// Scan lines y = const over the unit square, points about 1/(n - 1) apart along x with jitter,
// over gentle terrain plus `height(x, y)`; `disk`: only the points within the inscribed disk
// (lines clipped by a boundary, of different lengths).
template <class Height>
Rows scan(int rows_count, int n, Height height, std::uint32_t seed, bool disk = false) {
  Uniform r(seed);
  Rows rows;
  for (int j = 0; j < rows_count; ++j) {
    const double y = disk ? 0.05 + 0.9 * j / (rows_count - 1.0) : j / (rows_count - 1.0);
    for (int k = 0; k < n; ++k) {
      const double x = (k + r(-0.2, 0.2)) / (n - 1.0);
      if (disk && std::hypot(x - 0.5, y - 0.5) > 0.5) continue;
      rows.push_point(Point(x, y, 0.05 * std::sin(3 * x) * std::cos(2 * y) + height(x, y)));
    }
    rows.end_row();
  }
  return rows;
}

// Flat roofs (0.1 ... 0.3 high, 0.05 ... 0.15 wide) and conical trees (0.05 ... 0.1 high,
// radius 0.01 ... 0.03), placed at random: a LiDAR tile in small.
struct Town {
  double bx[12], by[12], bw[12], bd[12], bh[12];
  double tx[60], ty[60], tr[60], th[60];
  explicit Town(std::uint32_t seed) {
    Uniform r(seed);
    for (int k = 0; k < 12; ++k) {
      bx[k] = r(0.05, 0.95), by[k] = r(0.05, 0.95), bw[k] = r(0.05, 0.15);
      bd[k] = r(0.05, 0.15), bh[k] = r(0.1, 0.3);
    }
    for (int k = 0; k < 60; ++k)
      tx[k] = r(0, 1), ty[k] = r(0, 1), tr[k] = r(0.01, 0.03), th[k] = r(0.05, 0.1);
  }
  double operator()(double x, double y) const {
    double z = 0;
    for (int k = 0; k < 12; ++k)
      if (std::abs(x - bx[k]) < bw[k] / 2 && std::abs(y - by[k]) < bd[k] / 2) z += bh[k];
    for (int k = 0; k < 60; ++k) {
      const double d = std::hypot(x - tx[k], y - ty[k]) / tr[k];
      if (d < 1) z += th[k] * (1 - d);
    }
    return z;
  }
};

bool forced(const Rows& rows, double t, std::string& why, bool closed_u = false) {
  const detail::Centring c = detail::centre_rows(rows, 1);
  FitOptions o = at_t(t);
  o.closed_u = closed_u;
  return detail::jumps_force_interpolation(c.centred, o, c.roundoff, why);
}

TEST(JumpSpread, RoofsAndTreesForceKnotLinesEverywhere) {
  const Rows rows = scan(60, 80, Town(3), 3);
  std::string why;
  EXPECT_TRUE(forced(rows, 0.002, why)) << why;
  EXPECT_NE(why.find("farther than 2 T"), std::string::npos) << why;
  const detail::Centring c = detail::centre_rows(rows, 1);
  const detail::JumpSpread js = detail::jump_spread(c.centred, at_t(0.002), c.roundoff, 2);
  EXPECT_EQ(js.rows, 60);
  EXPECT_EQ(js.bins, 80);
  // A minority of the points jumps: the median point is on smooth ground or a flat roof.
  EXPECT_LT(js.jumps, js.points / 4);
  EXPECT_GE(2 * js.rows_hit, js.rows);
  EXPECT_GE(2 * js.bins_hit, js.bins);
  // At a T above the roofs' and trees' heights nothing jumps.
  EXPECT_FALSE(forced(rows, 0.5, why)) << why;
}

TEST(JumpSpread, AStepAtOnePlaceOfEveryRowDoesNot) {
  // A cliff across the rows at x = 0.5: every row jumps there, knot lines at one u suffice.
  const Rows rows = scan(
      60, 80, [](double x, double) { return x < 0.5 ? 0.0 : 0.2; }, 4);
  std::string why;
  EXPECT_FALSE(forced(rows, 0.002, why)) << why;
  const detail::Centring c = detail::centre_rows(rows, 1);
  const detail::JumpSpread js = detail::jump_spread(c.centred, at_t(0.002), c.roundoff, 2);
  EXPECT_GE(js.rows_hit, 55);  // the cliff is seen in (nearly) every row
  EXPECT_LE(js.bins_hit, 6);   // at the same place of each
}

TEST(JumpSpread, SpikesScatteredOverTheDataDo) {
  // 150 narrow spikes (one to three points wide, 20 ... 50 T high) at random over smooth
  // ground: each needs knot lines on either side of it, along and across the rows.
  Uniform r(11);
  double sx[150], sy[150], sh[150];
  for (int k = 0; k < 150; ++k) sx[k] = r(0, 1), sy[k] = r(0, 1), sh[k] = r(0.04, 0.1);
  // The first `count` of them.
  const auto spikes = [&](int count) {
    return [&, count](double x, double y) {
      double z = 0;
      for (int k = 0; k < count; ++k) {
        const double d = std::hypot(x - sx[k], y - sy[k]) / 0.02;
        if (d < 1) z += sh[k] * (1 - d);
      }
      return z;
    };
  };
  const Rows rows = scan(60, 80, spikes(150), 8);
  std::string why;
  EXPECT_TRUE(forced(rows, 0.002, why)) << why;
  // The same spikes, fewer: 10 of them leave most rows and most of a row's length calm.
  EXPECT_FALSE(forced(scan(60, 80, spikes(10), 8), 0.002, why)) << why;
}

TEST(JumpSpread, NoiseWithinTDoesNot) {
  Uniform r(9);
  const Rows rows = scan(
      60, 80, [&](double, double) { return r(-0.0018, 0.0018); }, 5);
  std::string why;
  EXPECT_FALSE(forced(rows, 0.002, why)) << why;
}

TEST(JumpSpread, SectionsFarApartOverACurvedBodyDoNot) {
  // 12 closed sections of 200 points of a body whose radius swells along it: the sections are
  // far apart for its curvature, so the quadric through a point's neighbours (its own and the
  // next sections') is loose, while each section is smooth and densely sampled.
  Rows rows;
  for (int j = 0; j < 12; ++j) {
    const double x = j / 11.0, radius = 0.2 + 0.3 * std::sin(3.1 * x);
    for (int k = 0; k < 200; ++k) {
      const double a = 2 * M_PI * k / 200;
      rows.push_point(Point(x, radius * std::cos(a), 0.7 * radius * std::sin(a)));
    }
    rows.end_row();
  }
  std::string why;
  EXPECT_FALSE(forced(rows, 1e-4, why, true)) << why;
}

TEST(JumpSpread, TheDefaultSaysWhyItIsAboveThePoints) {
  const Rows rows = scan(30, 50, Town(7), 6, true);
  FitOptions o = at_t(0.001);
  const FitResult f = fit_surface(rows, o);
  ASSERT_TRUE(f.report.within_tolerance);
  EXPECT_EQ(f.report.fold, 0.0);
  // Lines clipped by the disk: interpolating them takes the longest line's count on every line,
  // more than the points; nothing smaller holds T (the nearest below the points misses it by
  // two orders of magnitude), and the report says why.
  EXPECT_GT(test::size_of(f), static_cast<long>(rows.total_points()));
  EXPECT_NE(f.report.stop_reason.find("T forces interpolation, the data's jumps"),
            std::string::npos)
      << f.report.stop_reason;
  EXPECT_NE(f.report.stop_reason.find("in 97 % of the rows"), std::string::npos)
      << f.report.stop_reason;
}

}  // namespace
}  // namespace sfit
