// The parametrization rules beyond the paper (docs/method.md 7.4) in the curve stage and the whole
// surface fit: the tolerance at every point, minimal counts at the positions, the fallback to
// the paper's rule, and what the rules are for (fewer control points on uneven rows).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "parameters.h"
#include "sfit/error.h"
#include "sfit/incremental.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

using std::numbers::pi;
using test::reference_deviation;

constexpr Parametrization kGeometric[] = {Parametrization::kUniform, Parametrization::kChord,
                                          Parametrization::kCentripetal};

// A bulging half-tube in M rows of 0.75 ... 1.25 x `mean` points, each row sampled unevenly
// with its own phase (the layout of bench/peers' generated ragged sets): the point's index
// says little about where it is along the row.
Rows uneven_rows(int M, int mean, std::uint32_t seed = 3) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1e-4);
  Rows rows;
  for (int j = 0; j < M; ++j) {
    const double t = static_cast<double>(j) / (M - 1);
    const int n = std::max(
        6, static_cast<int>(std::lround(mean * (0.75 + 0.5 * std::fmod(j * 0.6180339887, 1.0)))));
    const double radius = 3.0 + 0.8 * std::sin(2.5 * pi * t);
    for (int k = 0; k < n; ++k) {
      const double u = static_cast<double>(k) / (n - 1);
      const double s = u + 0.05 * std::sin(2 * pi * u) * std::sin(1.7 * j + 0.3);
      const double th = pi * s;
      rows.push_point(
          Point(10 * t + 0.3 * std::sin(th) * std::sin(3 * t) + noise(rng),
                radius * std::cos(th) + noise(rng),
                radius * std::sin(th) * (1 + 0.1 * std::sin(3 * th + 4 * t)) + noise(rng)));
    }
    rows.end_row();
  }
  return rows;
}

Point saddle(double s, double t) {
  return Point(10 * s, 8 * t, std::sin(3 * s) * std::cos(2 * t) + s * t);
}
Point torus(double s, double t) {
  const double a = 2 * pi * s, b = 2 * pi * t;
  return Point((3 + std::cos(a)) * std::cos(b), (3 + std::cos(a)) * std::sin(b), std::sin(a));
}
Point tube(double s, double t) {  // closed rows (s round), open sequence
  return Point(2 * std::cos(2 * pi * s), 1.5 * std::sin(2 * pi * s), 5 * t * t);
}
Point tube_along(double s, double t) {  // open rows, closed sequence
  return tube(t, s);
}

TEST(GeometricParameters, EveryRuleHoldsTheToleranceInAllFourTopologies) {
  struct Case {
    Point (*f)(double, double);
    bool cu, cv;
  };
  for (const Case& c : {Case{saddle, false, false}, Case{tube, true, false},
                        Case{tube_along, false, true}, Case{torus, true, true}})
    for (Parametrization rule : kGeometric)
      for (double rel : {1e-2, 1e-4}) {
        const Rows rows =
            test::sample_rows(c.f, {31, 40, 35, 52, 44, 38, 47, 33, 41, 36}, c.cu, c.cv);
        FitOptions o;
        o.closed_u = c.cu;
        o.closed_v = c.cv;
        o.parametrization = rule;
        o.tolerance = relative_tolerance(rows, rel);
        const FitResult fit = fit_surface(rows, o);
        SCOPED_TRACE(std::string(to_string(rule)) + " closed " + std::to_string(c.cu) +
                     std::to_string(c.cv) + " T " + std::to_string(rel));
        EXPECT_TRUE(fit.report.within_tolerance);
        // Smooth data: no fallback, except centripetal positions across the tube's rows
        // (bunched at the bottom, z = 5 t^2) at 1e-4, whose interpolating columns swing out of
        // the data's box: the paper's rule then fits (SurfaceStaysNearTheDataBetweenThePoints).
        if (rule != Parametrization::kCentripetal || c.cv || !c.cu || rel != 1e-4) {
          EXPECT_EQ(fit.report.parametrization, rule);
        } else {
          EXPECT_EQ(fit.report.parametrization, Parametrization::kPaper);
        }
        EXPECT_TRUE(
            (reference_deviation(fit, rows).array() <= o.tolerance.array() * (1 + 1e-9)).all());
      }
}

TEST(GeometricParameters, ChordLengthNeedsFarFewerControlPointsOnUnevenRows) {
  const Rows rows = uneven_rows(40, 80);
  for (double rel : {1e-2, 1e-3}) {
    FitOptions o;
    o.method = FitMethod::kSfit01;  // the two stages at each rule
    o.tolerance = relative_tolerance(rows, rel);
    const FitResult paper = fit_surface(rows, o);
    o.parametrization = Parametrization::kChord;
    const FitResult chord = fit_surface(rows, o);
    SCOPED_TRACE(rel);
    ASSERT_TRUE(paper.report.within_tolerance);
    ASSERT_TRUE(chord.report.within_tolerance);
    EXPECT_EQ(chord.report.parametrization, Parametrization::kChord);
    EXPECT_TRUE(
        (reference_deviation(chord, rows).array() <= o.tolerance.array() * (1 + 1e-9)).all());
    const int p = paper.surface.count_u * paper.surface.count_v;
    const int c = chord.surface.count_u * chord.surface.count_v;
    // The paper's index rule lets each row's uneven sampling into the columns of control
    // points, which then need nearly one control point per row.
    EXPECT_LE(4 * c, p) << "chord " << chord.surface.count_u << "x" << chord.surface.count_v
                        << ", paper " << paper.surface.count_u << "x" << paper.surface.count_v;
  }
}

TEST(GeometricParameters, RowCountsAreMinimalAtThePositions) {
  const Rows rows = uneven_rows(6, 70);
  for (Parametrization rule : kGeometric) {
    FitOptions o;
    o.search = CountSearch::kLinear;
    o.parametrization = rule;
    o.tolerance = relative_tolerance(rows, 1e-4);
    const FitResult fit = fit_surface(rows, o);
    ASSERT_EQ(fit.report.parametrization, rule);
    const Point bound = 0.5 * o.tolerance * (1 - 1e-9);
    for (std::size_t j = 0; j < rows.size(); ++j) {
      const auto f = normalized_positions(rows[j], rule, false);
      const int c = fit.report.row_counts[j];
      // A count whose system the positions leave ill-conditioned does not hold either.
      const auto holds = [&](int count) {
        try {
          return (fit_curve_with_count(rows[j], 3, false, count, f).max_deviation.array() <=
                  bound.array())
              .all();
        } catch (const Error&) {
          return false;
        }
      };
      SCOPED_TRACE(std::string(to_string(rule)) + " row " + std::to_string(j));
      EXPECT_TRUE(holds(c));
      if (c > 4) {
        EXPECT_FALSE(holds(c - 1));
      }
    }
  }
}

TEST(GeometricParameters, InterpolantFallsBackToThePaperWhereThePositionsAdmitNone) {
  // A zigzag of six points within 0.03 of each other along a row 11 long: at chord positions they
  // fall into one knot span of any uniform curve, which cannot pass through them all.
  std::vector<Point> row;
  for (int k = 0; k < 6; ++k) row.emplace_back(k, 0.1 * k, 0);
  for (int i = 0; i < 6; ++i) row.emplace_back(6 + 0.001 * i, 0.6, i % 2 ? 0.002 : -0.002);
  for (int k = 7; k < 12; ++k) row.emplace_back(k, 0.1 * k, 0);
  const auto f = normalized_positions(row, Parametrization::kChord, false);
  ASSERT_LT(f[11] - f[6], 0.01);
  CurveFitOptions co;
  co.positions = f;
  co.bound = Point::Constant(1e-12);
  const CurveFit fit = fit_curve(row, co);
  EXPECT_EQ(fit.curve.count(), static_cast<int>(row.size()));
  EXPECT_FALSE(fit.scaled);
  EXPECT_EQ(fit.parameters,
            paper_parameters(3, fit.curve.count(), false, static_cast<int>(row.size())));
  EXPECT_LE(fit.max_deviation.maxCoeff(), 1e-12);
}

TEST(GeometricParameters, WholeFitFallsBackToThePaperAndSaysSo) {
  // Centripetal positions across the tube's rows at 1e-4: the fit holds every point but its
  // interpolating columns swing out of the data's box between the rows, so the paper's rule
  // fits instead, bit for bit, and the report says so.
  const Rows rows = test::sample_rows(tube, {31, 40, 35, 52, 44, 38, 47, 33, 41, 36}, true, false);
  FitOptions o;
  o.method = FitMethod::kSfit01;  // the two-stage method's fallback
  o.closed_u = true;
  o.tolerance = relative_tolerance(rows, 1e-4);
  const FitResult paper = fit_surface(rows, o);
  o.parametrization = Parametrization::kCentripetal;
  const FitResult centripetal = fit_surface(rows, o);
  ASSERT_TRUE(centripetal.report.within_tolerance);
  EXPECT_EQ(centripetal.report.parametrization, Parametrization::kPaper);
  test::expect_same_surface(centripetal, paper);
}

TEST(GeometricParameters, ZeroToleranceInterpolatesWithEveryRule) {
  const Rows rows = uneven_rows(12, 20);
  for (Parametrization rule : kGeometric) {
    FitOptions o;
    o.tolerance = Point::Zero();
    o.parametrization = rule;
    const FitResult fit = fit_surface(rows, o);
    SCOPED_TRACE(std::string(to_string(rule)) + ", used " +
                 std::string(to_string(fit.report.parametrization)));
    ASSERT_TRUE(fit.report.within_tolerance);
    EXPECT_LE(reference_deviation(fit, rows).maxCoeff(), 1e-9 * bounding_box(rows).diagonal());
  }
}

TEST(GeometricParameters, FewestKeepsTheSmallestSurfaceOfTheFourRules) {
  const Rows rows = uneven_rows(20, 50);
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  long smallest = 0;
  Parametrization smallest_rule = Parametrization::kPaper;
  for (Parametrization rule : {Parametrization::kPaper, Parametrization::kUniform,
                               Parametrization::kChord, Parametrization::kCentripetal}) {
    o.parametrization = rule;
    const FitResult r = fit_surface(rows, o);
    ASSERT_TRUE(r.report.within_tolerance);
    const long size = static_cast<long>(r.surface.count_u) * r.surface.count_v;
    if (smallest == 0 || size < smallest) {
      smallest = size;
      smallest_rule = r.report.parametrization;
    }
  }
  o.parametrization = Parametrization::kFewest;
  const FitResult best = fit_surface(rows, o);
  EXPECT_TRUE(best.report.within_tolerance);
  EXPECT_EQ(static_cast<long>(best.surface.count_u) * best.surface.count_v, smallest);
  EXPECT_EQ(best.report.parametrization, smallest_rule);
  EXPECT_NE(best.report.parametrization, Parametrization::kPaper);  // uneven rows: not the paper's
  // IncrementalFit with kFewest refits in full, so it stays the full fit's.
  IncrementalFit inc(rows, o);
  inc.move_point(4, 10, rows[4][10] + Point(0.001, 0, 0.002));
  const FitResult full = fit_surface(inc.rows(), o);
  test::expect_same_surface(inc.result(), full);
  EXPECT_EQ(inc.result().report.parametrization, full.report.parametrization);
}

TEST(GeometricParameters, SurfaceStaysNearTheDataBetweenThePoints) {
  // Chord length on the topobathy grid (steep shelf edges, rows sampled evenly in x and y, so
  // chord positions bunch where the terrain is flat) once gave a surface within T at every data
  // point that reached 1e9 between them. Ill-conditioned counts now fail, and a surface that
  // leaves the data's box by more than 1/10 of its diagonal where sfit samples it falls back to
  // the paper's rule: sampled far more densely here, every surface stays within 0.15.
  const std::vector<Rows> sets = {uneven_rows(20, 50),
                                  test::load_rows(test::example("topobathy.rows"))};
  for (const Rows& rows : sets)
    for (Parametrization rule : kGeometric)
      for (double rel : {1e-2, 1e-3}) {
        FitOptions o;
        o.parametrization = rule;
        o.tolerance = relative_tolerance(rows, rel);
        const FitResult fit = fit_surface(rows, o);
        ASSERT_TRUE(fit.report.within_tolerance);
        const BoundingBox box = bounding_box(rows);
        const double margin = 0.15 * box.diagonal();
        const Surface& s = fit.surface;
        Point lo = Point::Constant(INFINITY), hi = Point::Constant(-INFINITY);
        for (int a = 0; a <= 300; ++a)
          for (int b = 0; b <= 300; ++b) {
            const Point p = s.evaluate(s.u_end() * a / 300.0, s.v_end() * b / 300.0);
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
          }
        SCOPED_TRACE(std::string(to_string(rule)) + " " + std::to_string(rows.total_points()) +
                     " points, T " + std::to_string(rel) + ", used " +
                     std::string(to_string(fit.report.parametrization)));
        EXPECT_TRUE((lo.array() >= (box.min - Point::Constant(margin)).array()).all())
            << lo.transpose();
        EXPECT_TRUE((hi.array() <= (box.max + Point::Constant(margin)).array()).all())
            << hi.transpose();
      }
}

TEST(GeometricParameters, ResultDoesNotDependOnThreadCount) {
  const Rows rows = uneven_rows(200, 130);  // > 20000 points: the parallel path
  FitOptions o;
  o.parametrization = Parametrization::kChord;
  o.tolerance = relative_tolerance(rows, 1e-3);
  o.threads = 1;
  const FitResult one = fit_surface(rows, o);
  o.threads = 2;
  const FitResult two = fit_surface(rows, o);
  test::expect_same_surface(one, two);
}

TEST(GeometricParameters, IncrementalEditsGiveExactlyTheFullRefit) {
  for (Parametrization rule : {Parametrization::kUniform, Parametrization::kChord}) {
    FitOptions o;
    o.parametrization = rule;
    const Rows start = uneven_rows(12, 40);
    o.tolerance = relative_tolerance(start, 1e-3);
    IncrementalFit inc(start, o);
    std::mt19937 rng(11);
    for (int edit = 0; edit < 24; ++edit) {
      const std::size_t j = rng() % inc.rows().size();
      const std::size_t k = 1 + rng() % (inc.rows()[j].size() - 2);
      const Point p = inc.rows()[j][k];
      if (edit % 3 == 0) inc.move_point(j, k, p + Point(0.002, -0.003, 0.004));
      if (edit % 3 == 1) inc.insert_point(j, k, 0.5 * (p + inc.rows()[j][k - 1]));
      if (edit % 3 == 2) inc.erase_point(j, k);
      const FitResult full = fit_surface(inc.rows(), o);
      const FitResult& r = inc.result();
      SCOPED_TRACE(std::string(to_string(rule)) + " edit " + std::to_string(edit));
      test::expect_same_surface(r, full);
      EXPECT_EQ(r.report.parametrization, full.report.parametrization);
      EXPECT_TRUE(r.report.within_tolerance);
      if (HasFailure()) return;
    }
  }
}

}  // namespace
}  // namespace sfit
