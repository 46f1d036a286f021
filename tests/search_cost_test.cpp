// What the surface search costs where it cannot win (surface_method.cpp, count_floor.h), and
// that its answer does not depend on the thread count on the sampled path (above 5e4 points).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "pair_search.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

using test::expect_same_surface;

// A side x side grid, z a smooth field plus uniform noise of +-amplitude/2 (a fixed LCG).
Rows noisy_grid(int side, double amplitude) {
  Rows rows;
  unsigned long long state = 12345;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      const double u = static_cast<double>(state >> 11) / 9007199254740992.0;
      rows.push_point(
          Point(i, j, 10 * std::sin(0.01 * i) * std::cos(0.013 * j) + amplitude * (u - 0.5)));
    }
    rows.end_row();
  }
  return rows;
}

// Noise as large as T (+-0.5 at T = 0.5) on 62500 points: the rows alone need most of their
// points, far more than the search's sample of every 2nd point can reach, so the default
// searches no pair of the row rules, says so, and returns the two stages' surface bit for bit.
TEST(SearchCost, NoiseNearTSearchesNoRowRuleAndSaysSo) {
  const Rows rows = noisy_grid(250, 1.0);
  FitOptions o;
  o.tolerance = Point::Constant(0.5);
  o.threads = 2;
  const FitResult fit = fit_surface(rows, o);
  EXPECT_EQ(fit.report.method, FitMethod::kSfit01);
  // The row rules' floors rule them out, and the geometric rule's too: its floor (the rows'
  // at chord positions, times the columns') is beyond the largest pair it tries.
  EXPECT_NE(fit.report.stop_reason.find("no pair searched"), std::string::npos)
      << fit.report.stop_reason;
  // No pair solved at all (the floors are curve fits of a few rows, no surface solve).
  EXPECT_EQ(fit.report.pairs_tried, 0);
  EXPECT_TRUE(fit.report.within_tolerance);
  // T held at every point, measured on the returned surface.
  for (int a = 0; a < 3; ++a) EXPECT_LE(fit.report.max_deviation[a], 0.5);
  // The two stages, or where it has fewer control points their variant with the rows at all
  // of T and columns interpolating them (here 243 x 250 against 250 x 250), which says so.
  o.method = FitMethod::kSfit01;
  const FitResult two = fit_surface(rows, o);
  const bool variant = fit.report.stop_reason.find("the rows took all of T") != std::string::npos;
  if (variant) {
    EXPECT_LT(fit.surface.count_u * fit.surface.count_v, two.surface.count_u * two.surface.count_v);
    EXPECT_EQ(fit.surface.count_v, 250);
  } else {
    expect_same_surface(fit, two);
  }
}

// Less noise (+-0.2 at T = 0.5): the same grid is searched and beats the two stages.
TEST(SearchCost, LessNoiseIsSearched) {
  const Rows rows = noisy_grid(250, 0.4);
  FitOptions o;
  o.tolerance = Point::Constant(0.5);
  o.threads = 2;
  const FitResult fit = fit_surface(rows, o);
  EXPECT_GT(fit.report.pairs_tried, 0);
  EXPECT_EQ(fit.report.method, FitMethod::kSurface);
  EXPECT_TRUE(fit.report.within_tolerance);
  EXPECT_LT(fit.surface.count_u * fit.surface.count_v, 250 * 250 / 10);
}

// The default on 52000 points (searched on a sample, verified on all): the same bits, the
// same pairs and the same stop on 1 and 4 threads.
TEST(SearchCost, SampledSearchSameOnOneAndFourThreads) {
  const Rows rows = test::sample_rows(
      [](double s, double t) {
        return Point(10 * s, 8 * t, std::sin(7 * s) * std::cos(5 * t) + 0.3 * std::sin(19 * s * t));
      },
      std::vector<int>(200, 260));
  std::vector<FitResult> fits;
  for (int threads : {1, 4}) {
    FitOptions o;
    o.tolerance = Point::Constant(1e-3);
    o.threads = threads;
    fits.push_back(fit_surface(rows, o));
  }
  expect_same_surface(fits[0], fits[1]);
  EXPECT_EQ(fits[0].report.pairs_tried, fits[1].report.pairs_tried);
  EXPECT_EQ(fits[0].report.stop_reason, fits[1].report.stop_reason);
  EXPECT_NE(fits[0].report.stop_reason.find("searched on every"), std::string::npos)
      << fits[0].report.stop_reason;
}

// The sampled search's stop reason names its step as an English ordinal.
TEST(SearchCost, SampledStopReasonSaysTheOrdinal) {
  for (const auto& [step, word] :
       std::vector<std::pair<int, std::string>>{{2, "every 2nd point"},
                                                {3, "every 3rd point"},
                                                {4, "every 4th point"},
                                                {11, "every 11th point"},
                                                {12, "every 12th point"},
                                                {20, "every 20th point"},
                                                {21, "every 21st point"},
                                                {102, "every 102nd point"},
                                                {113, "every 113th point"}}) {
    EXPECT_NE(detail::minimal_on_sample(step).find(word), std::string::npos)
        << detail::minimal_on_sample(step);
  }
}

}  // namespace
}  // namespace sfit
