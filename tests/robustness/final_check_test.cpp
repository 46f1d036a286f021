// The guarantee is never false: the final check runs on the surface as returned and written
// (the data's coordinates), the round-off allowance applies at T = 0 only, and an offset that
// leaves too few digits for T is refused (kInputData, exit 5). Weights out of their range are
// input faults, not singular systems; the lower bound's count scan is bounded.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "reference_eval.h"
#include "sfit/curve_fit.h"
#include "sfit/error.h"
#include "sfit/fit_check.h"
#include "sfit/io/surface_json.h"
#include "sfit/surface_fit.h"
#include "sfit/weights.h"
#include "test_support.h"

namespace sfit {
namespace {

// The 6 x 5 grid of a shape about 5 units across, moved by `offset` on every axis.
Rows grid(double offset) {
  return test::sample_rows(
      [&](double s, double t) {
        return Point(offset + 5 * s, offset + 4 * t,
                     offset + std::sin(4.5 * s) * std::cos(2.8 * t) + 2 * s * t);
      },
      std::vector<int>(5, 6));
}

// Largest |S - D| / T per point and axis of the surface read back from its JSON text, by the
// tests' own evaluator (T = 0: relative to the report's round-off allowance).
double worst_ratio_as_written(const FitResult& f, const Rows& rows, const Point& tol) {
  const test::ReferenceSurface ref =
      test::reference_from_json_text(io::surface_json_text(f.surface, &f.report));
  double worst = 0;
  for (std::size_t j = 0, i = 0; j < rows.size(); ++j)
    for (std::size_t k = 0; k < rows[j].size(); ++k, ++i) {
      const auto p = ref.evaluate(f.u[i], f.point_v(j, i));
      for (int a = 0; a < 3; ++a) {
        const double limit = tol[a] > 0 ? tol[a] : f.report.roundoff;
        worst = std::max(worst, std::fabs(p[a] - rows[j][k][a]) / limit);
      }
    }
  return worst;
}

std::string refusal(const Rows& rows, const FitOptions& o) {
  try {
    const FitResult f = fit_surface(rows, o);
    return "no refusal: within " + std::to_string(f.report.within_tolerance) + ", worst ratio " +
           std::to_string(worst_ratio_as_written(f, rows, o.tolerance));
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputData) << e.what();
    return e.what();
  }
}

TEST(FinalCheck, LargeOffsetsAreRefusedNotClaimed) {
  for (const FitMethod m : {FitMethod::kSurface, FitMethod::kSfit01}) {
    FitOptions o;
    o.method = m;
    const Rows at15 = grid(1e15), at16 = grid(1e16), at12 = grid(1e12);
    o.tolerance = relative_tolerance(at15, 1e-3);  // 7.5e-3: doubles are 0.125 apart at 1e15
    EXPECT_EQ(refusal(at15, o),
              "the data lie 1e+15 from the origin on x, where doubles are 0.125 apart: too few "
              "digits for the tolerance 0.00748; move the data nearer the origin or raise the "
              "tolerance");
    o.tolerance = relative_tolerance(at16, 1e-3);
    EXPECT_EQ(refusal(at16, o).substr(0, 32), "the data lie 1e+16 from the orig");
    o.tolerance = Point::Zero();  // round-off allowance 7.5e-10, doubles 1.2e-4 apart at 1e12
    EXPECT_EQ(refusal(at12, o),
              "the data lie 1e+12 from the origin on x, where doubles are 0.000122 apart: too "
              "few digits for the tolerance 0 (round-off allowance 7.5e-10); move the data "
              "nearer the origin or raise the tolerance");
  }
}

// Offsets where doubles are finer than T, but not by much: the final check on the surface
// as written decides; whatever it says, a surface returned holds T as written.
TEST(FinalCheck, WhatIsReturnedHoldsAsWritten) {
  int held = 0, refused = 0;
  for (const double offset : {1e9, 1e10, 1e11, 1e12, 1e13, 3e13, 1e14})
    for (const FitMethod m : {FitMethod::kSurface, FitMethod::kSfit01}) {
      const Rows rows = grid(offset);
      FitOptions o;
      o.method = m;
      o.tolerance = relative_tolerance(rows, 1e-3);
      SCOPED_TRACE("offset " + std::to_string(offset));
      try {
        const FitResult f = fit_surface(rows, o);
        ASSERT_TRUE(f.report.within_tolerance);
        EXPECT_LE(worst_ratio_as_written(f, rows, o.tolerance), 1.0);
        ++held;
      } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInputData) << e.what();
        ++refused;
      }
    }
  EXPECT_GT(held, 0);
}

// sfit/fit_check.h: the final check for a surface made outside a fit (the editor's drag
// refit) is the fit's own: on a fit as returned it gives the report's verdict and deviations,
// and a point exactly at T does not hold once the round-off of evaluating it is allowed for.
TEST(FinalCheck, ThePublicCheckIsTheFitsOwn) {
  for (const double offset : {0.0, 1e6, 1e11}) {
    SCOPED_TRACE("offset " + std::to_string(offset));
    const Rows rows = grid(offset);
    FitOptions o;
    o.tolerance = relative_tolerance(rows, 1e-3);
    const FitResult f = fit_surface(rows, o);
    ASSERT_TRUE(f.report.within_tolerance);
    FitResult c = f;
    c.report.within_tolerance = false;
    c.report.max_deviation = Point::Zero();
    check_fit_as_written(c, rows, o.tolerance, 1);
    EXPECT_TRUE(c.report.within_tolerance);
    EXPECT_EQ(c.report.max_deviation, f.report.max_deviation);
    EXPECT_EQ(c.report.worst_row, f.report.worst_row);
    EXPECT_EQ(c.report.worst_index, f.report.worst_index);
    // T equal to the largest deviation: a naive |d| <= T holds, the check does not.
    const Point at_t = f.report.max_deviation;
    check_fit_as_written(c, rows, at_t, 1);
    EXPECT_FALSE(c.report.within_tolerance);
    // The verdict is the same on every thread count.
    FitResult c4 = f;
    check_fit_as_written(c4, rows, at_t, 4);
    EXPECT_EQ(c4.report.within_tolerance, c.report.within_tolerance);
    EXPECT_EQ(c4.report.max_deviation, c.report.max_deviation);
    // A surface moved by 2 T on z holds nowhere.
    FitResult moved = f;
    for (Point& p : moved.surface.control) p.z() += 2 * o.tolerance.z();
    check_fit_as_written(moved, rows, o.tolerance);
    EXPECT_FALSE(moved.report.within_tolerance);
    EXPECT_GT(moved.report.max_deviation.z(), o.tolerance.z());
  }
}

// The round-off allowance (1e-10 of the diagonal) is not added to a tolerance > 0: at
// T = 1e-12 (far below it) the fit is either within T itself or says it is not.
TEST(FinalCheck, NoRoundoffAllowanceAboveZeroTolerance) {
  const Rows rows = grid(0);
  FitOptions o;
  o.degree_u = o.degree_v = 20;
  o.closed_u = o.closed_v = true;
  o.tolerance = Point::Constant(1e-12);
  try {
    const FitResult f = fit_surface(rows, o);
    if (f.report.within_tolerance) {
      EXPECT_LE(worst_ratio_as_written(f, rows, o.tolerance), 1.0);
    }
  } catch (const Error& e) {
    EXPECT_TRUE(e.code() == ErrorCode::kToleranceNotMet || e.code() == ErrorCode::kInputData)
        << e.what();
  }
  // T = 0 interpolates within the allowance, which the report states.
  o.degree_u = o.degree_v = 3;
  o.closed_u = o.closed_v = false;
  o.tolerance = Point::Zero();
  const FitResult f = fit_surface(rows, o);
  EXPECT_TRUE(f.report.within_tolerance);
  EXPECT_DOUBLE_EQ(f.report.roundoff, kRoundoffRelative * bounding_box(rows).diagonal());
  EXPECT_LE(worst_ratio_as_written(f, rows, o.tolerance), 1.0);
}

TEST(Weights, OutOfTheirRangeAreInputFaults) {
  for (const double w : {1e50, 1e308, 4.9e-324, 1e-310, 1e-7, 2e6}) {
    Rows rows = grid(0);
    std::vector<double> weights(rows.total_points(), 1.0);
    weights[7] = w;
    rows.set_weights(weights);
    FitOptions o;
    o.tolerance = relative_tolerance(rows, 1e-3);
    try {
      fit_surface(rows, o);
      ADD_FAILURE() << "weight " << w << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kInputData) << e.what();
      EXPECT_EQ(e.place().row, 1);
      EXPECT_EQ(e.place().point, 1);
      EXPECT_EQ(e.message().substr(0, 39), "weight must be a number 1e-06 ... 1e+06") << e.what();
    }
  }
  // The ends of the range fit (each weight alone, and both together).
  const std::vector<std::pair<double, double>> ends = {
      {kMinWeight, 1.0}, {1.0, kMaxWeight}, {kMinWeight, kMaxWeight}};
  for (const auto& w : ends) {
    Rows rows = grid(0);
    std::vector<double> weights(rows.total_points(), w.first);
    for (std::size_t i = 0; i < weights.size(); i += 2) weights[i] = w.second;
    rows.set_weights(weights);
    for (const FitMethod m : {FitMethod::kSurface, FitMethod::kSfit01}) {
      FitOptions o;
      o.method = m;
      o.tolerance = relative_tolerance(rows, 1e-3);
      const FitResult f = fit_surface(rows, o);
      EXPECT_TRUE(f.report.within_tolerance);
    }
  }
}

// One outlier in a long row: the lower bound's linear scan stops after its limit of counts
// (one solve each), instead of one solve per count up to thousands.
TEST(LowerBound, TheLinearScanIsBounded) {
  std::vector<Point> row;
  const int n = 30000;
  for (int i = 0; i < n; ++i) {
    const double t = double(i) / (n - 1);
    row.emplace_back(10 * t, 0, std::sin(3 * t) + (i == n / 2 ? 5.0 : 0.0));
  }
  CurveFitOptions co;
  co.degree = 3;
  co.bound = Point::Constant(0.005);
  co.search = CountSearch::kLinear;
  co.linear_limit = 256;
  const CurveFit f = fit_curve(row, co);
  EXPECT_TRUE(f.curve.control.empty()) << "no count up to 259 holds the outlier";
  EXPECT_LE(f.solves, 256);
  // The fast search finds a count that holds, in few solves.
  co.search = CountSearch::kFast;
  const CurveFit fast = fit_curve(row, co);
  EXPECT_GT(fast.curve.count(), 259);
  EXPECT_LE(fast.solves, 64);
}

// Two rows of 30000 points with one outlier: a fit that held T after minutes of one solve per
// count in the lower bound now takes seconds (the bound on that work is asserted above;
// ctest's TIMEOUT bounds the whole, no time is asserted here).
TEST(LowerBound, TwoLongRowsWithAnOutlierFit) {
  Rows rows;
  const int n = 30000;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < n; ++i) {
      const double t = double(i) / (n - 1);
      rows.push_point(
          Point(10 * t, j, std::sin(3 * t) + 0.2 * j + (j == 0 && i == n / 2 ? 5.0 : 0.0)));
    }
    rows.end_row();
  }
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  const FitResult f = fit_surface(rows, o);
  EXPECT_TRUE(f.report.within_tolerance);
  // T at every point by the independent evaluator (at the points' own parameters), no fold.
  const Point dev = test::reference_deviation(f, rows);
  for (int a = 0; a < 3; ++a) EXPECT_LE(dev[a], o.tolerance[a] * (1 + 1e-9)) << "axis " << a;
  EXPECT_EQ(f.report.fold, 0.0);
  // Below the points (the two stages need more): one control point across per row at most
  // twice over, so the fallback's pairs stay cheap (docs/method.md 7.12).
  EXPECT_LT(static_cast<long>(f.surface.count_u) * f.surface.count_v, 2L * n);
  EXPECT_LE(f.surface.count_v, 4);
  // The report says what made the surface: the fallback below the points, or corner knots
  // (the outlier turns like a corner in its row; chord parameters give its rise and fall a
  // stretch of u between two creases).
  EXPECT_TRUE(f.report.stop_reason.find("below the points") != std::string::npos ||
              f.report.stop_reason.rfind("corner knots: ", 0) == 0)
      << f.report.stop_reason;
}

}  // namespace
}  // namespace sfit
