#include "sfit/surface_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "deviation.h"
#include "sfit/error.h"
#include "test_support.h"

namespace sfit {
namespace {

using std::numbers::pi;
using test::reference_deviation;
using test::sample_rows;

Point saddle(double s, double t) {
  return Point(10 * s, 8 * t, std::sin(3 * s) * std::cos(2 * t) + s * t);
}
// Cylinder of radius 2 around z: s goes round, t goes up.
Point cylinder(double s, double t) {
  return Point(2 * std::cos(2 * pi * s), 2 * std::sin(2 * pi * s), 5 * t);
}
// The same cylinder with rows along the axis (s up) and the row sequence going round (t).
Point cylinder_along(double s, double t) {
  return cylinder(t, s);
}
Point torus(double s, double t) {
  const double R = 3, r = 1;
  const double a = 2 * pi * s, b = 2 * pi * t;
  return Point((R + r * std::cos(a)) * std::cos(b), (R + r * std::cos(a)) * std::sin(b),
               r * std::sin(a));
}

struct Topology {
  const char* name;
  Point (*f)(double, double);
  bool cu, cv;
};
const Topology kTopologies[] = {{"open/open saddle", saddle, false, false},
                                {"closed/open cylinder", cylinder, true, false},
                                {"open/closed cylinder", cylinder_along, false, true},
                                {"closed/closed torus", torus, true, true}};

TEST(SurfaceFit, FourTopologiesHoldToleranceOnKnownSurfaces) {
  for (const auto& topo : kTopologies) {
    const std::vector<int> counts = {31, 40, 35, 52, 44, 38, 47, 33, 41, 36, 50, 39};
    const Rows rows = sample_rows(topo.f, counts, topo.cu, topo.cv);
    FitOptions o;
    o.closed_u = topo.cu;
    o.closed_v = topo.cv;
    o.tolerance = relative_tolerance(rows, 1e-3);
    const FitResult fit = fit_surface(rows, o);
    SCOPED_TRACE(topo.name);
    EXPECT_TRUE(fit.report.within_tolerance);
    EXPECT_TRUE((fit.report.max_deviation.array() <= o.tolerance.array()).all());
    const Point ref = reference_deviation(fit, rows);
    EXPECT_TRUE((ref.array() <= o.tolerance.array() * (1 + 1e-9)).all()) << ref.transpose();
    EXPECT_EQ(fit.surface.periodic_u, topo.cu);
    EXPECT_EQ(fit.surface.periodic_v, topo.cv);
    // A closed direction is closed and smooth across the seam.
    const Surface& s = fit.surface;
    for (double x : {0.1, 0.5, 0.77}) {
      if (topo.cu) {
        Point a[6], b[6];
        s.derivatives(0.0, x * s.v_end(), a);
        s.derivatives(s.u_end() - 1e-12, x * s.v_end(), b);
        EXPECT_NEAR((a[0] - b[0]).norm(), 0, 1e-9);
        EXPECT_NEAR((a[1] - b[1]).norm(), 0, 1e-6 * (1 + a[1].norm()));
      }
      if (topo.cv) {
        Point a[6], b[6];
        s.derivatives(x * s.u_end(), 0.0, a);
        s.derivatives(x * s.u_end(), s.v_end() - 1e-12, b);
        EXPECT_NEAR((a[0] - b[0]).norm(), 0, 1e-9);
        EXPECT_NEAR((a[2] - b[2]).norm(), 0, 1e-6 * (1 + a[2].norm()));
      }
    }
  }
}

TEST(SurfaceFit, ZeroToleranceReproducesEqualAndRaggedRows) {
  for (const auto& topo : kTopologies)
    for (bool ragged : {false, true}) {
      const std::vector<int> counts =
          ragged ? std::vector<int>{9, 17, 5, 12, 7, 21, 10} : std::vector<int>(7, 13);
      const Rows rows = sample_rows(topo.f, counts, topo.cu, topo.cv);
      FitOptions o;
      o.closed_u = topo.cu;
      o.closed_v = topo.cv;
      o.tolerance = Point::Zero();
      const FitResult fit = fit_surface(rows, o);
      SCOPED_TRACE(std::string(topo.name) + (ragged ? " ragged" : " equal"));
      EXPECT_TRUE(fit.report.within_tolerance);
      const double diag = bounding_box(rows).diagonal();
      EXPECT_LE(fit.report.max_deviation.maxCoeff(), 1e-9 * diag);
      EXPECT_LE(reference_deviation(fit, rows).maxCoeff(), 1e-9 * diag);
    }
}

TEST(SurfaceFit, PolesAndShortRows) {
  // A sphere by latitude rings, closed rows, with single-point poles at both ends and rows of
  // 3 and 4 points (fewer than degree + 1 = 6) near them.
  auto sphere = [](double s, double t) {
    const double lat = pi * (t - 0.5), lon = 2 * pi * s;
    return Point(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
  };
  const Rows rows = sample_rows(sphere, {1, 3, 4, 12, 20, 24, 20, 12, 4, 3, 1}, true, false);
  for (double tol : {0.0, 1e-4, 1e-2}) {
    FitOptions o;
    o.degree_u = o.degree_v = 5;
    o.closed_u = true;
    o.tolerance = Point::Constant(tol);
    const FitResult fit = fit_surface(rows, o);
    SCOPED_TRACE(tol);
    EXPECT_TRUE(fit.report.within_tolerance);
    EXPECT_EQ(fit.report.row_counts.front(), 1);  // the pole
    EXPECT_EQ(fit.report.row_counts[1], 3);       // interpolated at degree 2
    EXPECT_LE(reference_deviation(fit, rows).maxCoeff(), std::max(tol, 1e-9));
    if (tol == 0.0) {
      // At T = 0 the iso-curve of a pole row is the pole itself: a true degenerate edge.
      for (double u : {0.0, 1.3, 2.9})
        EXPECT_NEAR((fit.surface.evaluate(u, fit.v[0]) - rows[0][0]).norm(), 0, 1e-9);
    }
  }
}

TEST(SurfaceFit, DegreeOneAndTwenty) {
  const Rows rows = sample_rows(saddle, std::vector<int>(24, 40));
  for (int p : {1, 20}) {
    FitOptions o;
    o.degree_u = o.degree_v = p;
    o.tolerance = relative_tolerance(rows, 1e-3);
    const FitResult fit = fit_surface(rows, o);
    EXPECT_TRUE(fit.report.within_tolerance) << p;
    EXPECT_LE(reference_deviation(fit, rows, 3).maxCoeff(), o.tolerance.x() * (1 + 1e-9)) << p;
    EXPECT_GE(fit.surface.count_u, p + 1);
  }
}

TEST(SurfaceFit, RowCountsAreMinimalAtHalfTheTolerance) {
  const Rows rows = sample_rows(saddle, {30, 41, 25, 60, 33});
  FitOptions o;
  o.search = CountSearch::kLinear;
  o.tolerance = relative_tolerance(rows, 1e-4);
  const FitResult fit = fit_surface(rows, o);
  // The stage budget is T/2 with a 1e-9 relative margin (surface_fit.cpp).
  const Point bound = 0.5 * o.tolerance * (1 - 1e-9);
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const int c = fit.report.row_counts[j];
    const auto holds = [&](int count) {
      return (fit_curve_with_count(rows[j], 3, false, count).max_deviation.array() <= bound.array())
          .all();
    };
    EXPECT_TRUE(holds(c)) << j;
    if (c > 4) {
      EXPECT_FALSE(holds(c - 1)) << j;
    }
  }
}

TEST(SurfaceFit, ResultDoesNotDependOnThreadCount) {
  // Large enough (> 20000 points) for the parallel path.
  const Rows rows = sample_rows(saddle, std::vector<int>(150, 160));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-4);
  o.threads = 1;
  const FitResult one = fit_surface(rows, o);
  o.threads = 2;
  const FitResult two = fit_surface(rows, o);
  test::expect_same_surface(one, two);
  EXPECT_EQ(one.report.row_counts, two.report.row_counts);
  // The check alone, in row blocks on two threads: the same answer as one pass, also with a
  // non-finite deviation and ties for the worst point.
  for (bool poison : {false, true}) {
    Rows data = rows;
    if (poison)
      data = test::sample_rows(
          [](double s, double t) { return s > 0.5 && t > 0.7 ? Point(NAN, 0, 0) : saddle(s, t); },
          std::vector<int>(150, 160));
    const DeviationCheck a =
        check_deviation(one.surface, data, one.u, one.v, o.tolerance, 1e-12, 1);
    const DeviationCheck b =
        check_deviation(one.surface, data, one.u, one.v, o.tolerance, 1e-12, 2);
    SCOPED_TRACE(poison);
    EXPECT_EQ(a.within, b.within);
    EXPECT_EQ(a.worst_row, b.worst_row);
    EXPECT_EQ(a.worst_index, b.worst_index);
    EXPECT_EQ(a.worst_ratio, b.worst_ratio);
    EXPECT_EQ(a.max_deviation, b.max_deviation);
    if (poison) {
      EXPECT_FALSE(a.within);
    }
  }
}

TEST(SurfaceFit, InvalidInputAndOptionsAreRejectedWithPlace) {
  const Rows good = sample_rows(saddle, {5, 5, 5});
  auto code_of = [](const Rows& r, const FitOptions& o) {
    try {
      validate(r, o);
    } catch (const Error& e) {
      return e.code();
    }
    return ErrorCode::kInternal;  // not thrown
  };
  FitOptions o;
  o.degree_u = 0;
  EXPECT_EQ(code_of(good, o), ErrorCode::kUsage);
  o.degree_u = 21;
  EXPECT_EQ(code_of(good, o), ErrorCode::kUsage);
  o = {};
  o.tolerance = Point(0.1, -1, 0.1);
  EXPECT_EQ(code_of(good, o), ErrorCode::kUsage);
  o = {};
  EXPECT_EQ(code_of(sample_rows(saddle, {5}), o), ErrorCode::kInputData);  // one row
  o.closed_v = true;
  EXPECT_EQ(code_of(sample_rows(saddle, {5, 5}), o), ErrorCode::kInputData);
  o = {};
  o.closed_u = true;
  try {
    validate(sample_rows(saddle, {5, 2, 5}), o);
    FAIL() << "a closed row of 2 points was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputData);
    EXPECT_EQ(e.place().row, 1);
    EXPECT_NE(std::string(e.what()).find("at least 3 points"), std::string::npos);
  }
  Rows bad = sample_rows(saddle, {4, 4});
  bad.mutable_row(1)[2].y() = std::nan("");
  try {
    validate(bad, FitOptions{});
    FAIL() << "NaN accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputData);
    EXPECT_EQ(e.place().row, 1);
    EXPECT_EQ(e.place().point, 2);
  }
}

}  // namespace
}  // namespace sfit
