#include "sfit/incremental.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sfit/error.h"
#include "test_support.h"

namespace sfit {
namespace {

Point wavy(double s, double t) {
  return Point(20 * s, 12 * t, std::sin(5 * s) * std::cos(3 * t) + 0.5 * s * t);
}

// The incremental result must be fit_surface()'s, bit for bit.
void expect_same_as_full_fit(const IncrementalFit& inc, const FitOptions& o) {
  const FitResult full = fit_surface(inc.rows(), o);
  const FitResult& r = inc.result();
  test::expect_same_surface(r, full);
  EXPECT_EQ(r.report.row_counts, full.report.row_counts);
  EXPECT_EQ(r.report.column_counts, full.report.column_counts);
  EXPECT_EQ(r.report.max_deviation, full.report.max_deviation);
  EXPECT_EQ(r.report.within_tolerance, full.report.within_tolerance);
  EXPECT_TRUE(r.report.within_tolerance);
}

TEST(IncrementalFit, RandomEditsGiveExactlyTheFullRefit) {
  for (bool closed : {false, true}) {
    const Rows rows =
        test::sample_rows(wavy, {30, 34, 28, 40, 31, 36, 29, 33, 30, 35}, closed, false);
    FitOptions o;
    o.closed_u = closed;
    o.tolerance = relative_tolerance(rows, 1e-3);
    IncrementalFit inc(rows, o);
    std::mt19937 rng(7);
#if defined(__SANITIZE_ADDRESS__)
    const int edits = 16;  // each kind 4 times: AddressSanitizer runs the 40 in 85 s
#else
    const int edits = 40;
#endif
    for (int edit = 0; edit < edits; ++edit) {
      const std::size_t j = rng() % inc.rows().size();
      const std::size_t n = inc.rows()[j].size();
      const std::size_t k = 1 + rng() % (n - 2);  // interior: keeps the bounding box mostly
      const Point p = inc.rows()[j][k];
      SCOPED_TRACE("closed " + std::to_string(closed) + " edit " + std::to_string(edit));
      switch (edit % 4) {
        case 0:
          inc.move_point(j, k, p + Point(0.01, -0.02, 0.05));
          break;
        case 1:
          inc.insert_point(j, k, 0.5 * (p + inc.rows()[j][k - 1]));
          break;
        case 2:
          inc.erase_point(j, k);
          break;
        case 3: {
          std::vector<Point> row(inc.rows()[j].begin(), inc.rows()[j].end());
          for (Point& q : row) q.z() += 0.01;
          inc.replace_row(j, row);
          break;
        }
      }
      expect_same_as_full_fit(inc, o);
      if (HasFailure()) return;
    }
  }
}

TEST(IncrementalFit, MovingOnePointRefitsFewRows) {
  const Rows rows = test::sample_rows(wavy, std::vector<int>(40, 30));
  FitOptions o;
  o.method = FitMethod::kSfit01;  // the surface search refits in full
  o.tolerance = relative_tolerance(rows, 1e-3);
  IncrementalFit inc(rows, o);
  EXPECT_EQ(inc.rows_refitted(), 40u);
  inc.move_point(20, 15, inc.rows()[20][15] + Point(0, 0, 0.02));
  EXPECT_GE(inc.rows_refitted(), 1u);
  EXPECT_LE(inc.rows_refitted(), 16u);  // at most the rest of its block
  expect_same_as_full_fit(inc, o);
}

// The two-stage method's state (its registry entry's MethodState) under the driver: on open rows
// edits refit a few rows; on closed rows whose seams the driver re-orders, every fit is in
// full (the state forgets the re-ordered rows) and still the full refit's, bit for bit.
TEST(IncrementalFit, TwoStageStateUnderTheDriverMatchesTheFullRefit) {
  for (bool turned : {false, true}) {
    const Rows rows = turned ? test::sample_rows(
                                   [](double s, double t) {
                                     // rows start at turned seams: the driver aligns them
                                     const double a = 2 * M_PI * (s + 0.13 * std::round(9 * t));
                                     return Point(std::cos(a), std::sin(a), 2 * t);
                                   },
                                   std::vector<int>(10, 24), true)
                             : test::sample_rows(wavy, std::vector<int>(24, 30));
    FitOptions o;
    o.method = FitMethod::kSfit01;
    o.closed_u = turned;
    o.tolerance = relative_tolerance(rows, 1e-3);
    IncrementalFit inc(rows, o);
    ASSERT_EQ(inc.result().report.seams.empty(), !turned);
    EXPECT_EQ(inc.rows_refitted(), rows.size());
    std::mt19937 rng(11);
    for (int edit = 0; edit < 6; ++edit) {
      const std::size_t j = 1 + rng() % (inc.rows().size() - 2);
      const std::size_t k = 1 + rng() % (inc.rows()[j].size() - 2);
      SCOPED_TRACE("turned " + std::to_string(turned) + " edit " + std::to_string(edit));
      inc.move_point(j, k, inc.rows()[j][k] + Point(0, 0, 0.002));
      if (turned)
        EXPECT_EQ(inc.rows_refitted(), rows.size());  // re-ordered rows: in full every time
      else
        EXPECT_LE(inc.rows_refitted(), 16u);  // the edited row and the rest of its block
      expect_same_as_full_fit(inc, o);
      if (HasFailure()) return;
    }
  }
}

TEST(IncrementalFit, EditThatGrowsTheBoxStillMatches) {
  const Rows rows = test::sample_rows(wavy, std::vector<int>(8, 20));
  FitOptions o;
  o.tolerance = Point::Constant(0.01);
  IncrementalFit inc(rows, o);
  inc.move_point(3, 10, Point(10, 5, 40));  // far above everything: a new box, a full fit
  EXPECT_EQ(inc.rows_refitted(), 8u);
  expect_same_as_full_fit(inc, o);
}

TEST(IncrementalFit, BadEditsThrowAndKeepTheState) {
  const Rows rows = test::sample_rows(wavy, std::vector<int>(5, 10));
  FitOptions o;
  o.tolerance = Point::Constant(0.01);
  IncrementalFit inc(rows, o);
  const auto before = inc.result().surface.control;
  EXPECT_THROW(inc.move_point(9, 0, Point::Zero()), Error);
  EXPECT_THROW(inc.erase_point(0, 10), Error);
  EXPECT_THROW(inc.move_point(1, 2, Point(std::nan(""), 0, 0)), Error);
  EXPECT_EQ(inc.rows()[1][2], rows[1][2]);
  EXPECT_EQ(inc.result().surface.control, before);
  inc.move_point(1, 2, rows[1][2] + Point(0, 0, 0.001));  // still works afterwards
  expect_same_as_full_fit(inc, o);
}

}  // namespace
}  // namespace sfit
