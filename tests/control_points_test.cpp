// The default method, the surface search (FitMethod::kSurface, docs/control-points.md): the
// guarantee on every bundled data set, never more control points than the two stages, the
// minimality of the pair it stops at, T = 0, the four topologies, thread counts, fixed counts.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "below_points.h"
#include "search_frame.h"
#include "sfit/error.h"
#include "sfit/incremental.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

constexpr double pi = std::numbers::pi;

struct Bundled {
  const char* file;
  bool closed_u;
};
constexpr Bundled kBundled[] = {{"d150_wing.rows", true},
                                {"iea3p4mw_blade_ragged9.rows", true},
                                {"ship_px121_stations.rows", false},
                                {"table1_synthetic.rows", false}};

using test::size_of;

// Every point within T per axis by the independent evaluator, and by Surface::evaluate.
void expect_guarantee(const FitResult& fit, const Rows& rows, const Point& tol) {
  EXPECT_TRUE(fit.report.within_tolerance);
  EXPECT_TRUE((test::reference_deviation(fit, rows).array() <= tol.array() * (1 + 1e-9)).all());
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (std::size_t k = 0; k < rows[j].size(); ++k) {
      const Point d = (fit.surface.evaluate(fit.u[rows.offsets()[j] + k],
                                            fit.point_v(j, rows.offsets()[j] + k)) -
                       rows[j][k])
                          .cwiseAbs();
      ASSERT_TRUE((d.array() <= tol.array() * (1 + 1e-9)).all())
          << "row " << j << " point " << k << " deviation " << d.transpose();
    }
}

// At the chosen pair, one fewer in either direction fails under the same rule and norm;
// the fallback below the points (below_points.h) by its own criterion: the calm term, the
// corrected parameters, the guard and no fold.
void expect_minimal(const FitResult& fit, const Rows& rows, const FitOptions& base) {
  const FitReport& r = fit.report;
  // Corner knots' surface is not the search's pair: its own lowering (each stretch's spans,
  // then nv, while T holds) is tested in tests/corner_rows_test.cpp and corner_knots_test.cpp.
  if (r.method != FitMethod::kSurface || r.knots == KnotRule::kCorners) return;
  ASSERT_EQ(r.stop_reason.rfind("minimal", 0), 0u) << r.stop_reason;
  if (r.stop_reason.rfind("minimal below the points", 0) == 0) {
    const detail::Frame fr(rows, base);
    EXPECT_TRUE(detail::holds_below_points(fr, base, r.count_u, r.count_v));
    EXPECT_FALSE(detail::holds_below_points(fr, base, r.count_u - 1, r.count_v));
    EXPECT_FALSE(detail::holds_below_points(fr, base, r.count_u, r.count_v - 1));
    return;
  }
  FitOptions o = base;
  o.parametrization = r.parametrization;
  o.norm = r.norm;
  for (const auto& [nu, nv] :
       {std::pair{r.count_u - 1, r.count_v}, std::pair{r.count_u, r.count_v - 1}}) {
    if (nu < o.degree_u + 1 || nv < o.degree_v + 1) continue;
    o.counts = std::array<int, 2>{nu, nv};
    bool holds = false;  // as the search judges: T at every point and its guards pass
    try {
      const FitReport q = fit_surface(rows, o).report;
      holds = q.within_tolerance && q.stop_reason == "counts given";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kToleranceNotMet);  // singular: does not hold
    }
    EXPECT_FALSE(holds) << nu << " x " << nv << " holds too";
  }
}

class Bundles : public ::testing::TestWithParam<std::tuple<Bundled, double>> {};

TEST_P(Bundles, DefaultHoldsEveryPointWithNoMoreThanTheTwoStagesAndIsMinimal) {
  const auto [set, fraction] = GetParam();
  const Rows rows = test::load_rows(test::example(set.file));
  FitOptions o;
  o.closed_u = set.closed_u;
  o.tolerance = relative_tolerance(rows, fraction);
  const FitResult fit = fit_surface(rows, o);
  expect_guarantee(fit, rows, o.tolerance);
  FitOptions o1 = o;
  o1.method = FitMethod::kSfit01;
  const FitResult two = fit_surface(rows, o1);
  EXPECT_LE(size_of(fit), size_of(two));
  if (fit.report.method == FitMethod::kSfit01) {
    test::expect_same_surface(fit, two);  // nothing smaller held: the two stages' surface
    EXPECT_EQ(fit.report.stop_reason.rfind("sfit01", 0), 0u);
  }
  EXPECT_GT(fit.report.pairs_tried, 0);
  expect_minimal(fit, rows, o);
}

std::string bundle_name(const ::testing::TestParamInfo<std::tuple<Bundled, double>>& info) {
  std::string n = std::get<0>(info.param).file;
  n = n.substr(0, n.find('.'));
  const double f = std::get<1>(info.param);
  return n + (f == 1e-2 ? "_1em2" : f == 1e-3 ? "_1em3" : "_1em4");
}

INSTANTIATE_TEST_SUITE_P(Examples, Bundles,
                         ::testing::Combine(::testing::ValuesIn(kBundled),
                                            ::testing::Values(1e-2, 1e-3, 1e-4)),
                         bundle_name);

Point smooth_height(double s, double t) {
  return Point(40 * s, 30 * t, 3 * std::sin(6 * s + 1) * std::cos(5 * t) + 2 * s * t);
}
Point tube(double s, double t) {
  return Point(2 * std::cos(2 * pi * s), 1.5 * std::sin(2 * pi * s), 5 * t + 0.3 * t * t);
}
Point tube_along(double s, double t) {
  return tube(t, s);
}
Point torus(double s, double t) {
  const double a = 2 * pi * s, b = 2 * pi * t;
  return Point((3 + std::cos(a)) * std::cos(b), (3 + std::cos(a)) * std::sin(b), std::sin(a));
}

TEST(SurfaceSearch, SmoothGridNeedsFarFewerControlPointsThanTheTwoStages) {
  const Rows rows = test::sample_rows(smooth_height, std::vector<int>(60, 50));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-2);
  const FitResult fit = fit_surface(rows, o);
  expect_guarantee(fit, rows, o.tolerance);
  o.method = FitMethod::kSfit01;
  const FitResult two = fit_surface(rows, o);
  EXPECT_EQ(fit.report.method, FitMethod::kSurface);
  EXPECT_LE(2 * size_of(fit), size_of(two))
      << fit.surface.count_u << "x" << fit.surface.count_v << " against " << two.surface.count_u
      << "x" << two.surface.count_v;
  o.method = FitMethod::kSurface;
  expect_minimal(fit, rows, o);
}

TEST(SurfaceSearch, EveryTopologyHoldsAndIsMinimal) {
  struct Case {
    Point (*f)(double, double);
    bool cu, cv;
  };
  for (const Case& c : {Case{smooth_height, false, false}, Case{tube, true, false},
                        Case{tube_along, false, true}, Case{torus, true, true}})
    for (double rel : {1e-2, 1e-3}) {
      SCOPED_TRACE(::testing::Message() << c.cu << c.cv << " " << rel);
      const Rows rows =
          test::sample_rows(c.f, {31, 40, 35, 52, 44, 38, 47, 33, 41, 36, 39, 45}, c.cu, c.cv);
      FitOptions o;
      o.closed_u = c.cu;
      o.closed_v = c.cv;
      o.tolerance = relative_tolerance(rows, rel);
      const FitResult fit = fit_surface(rows, o);
      expect_guarantee(fit, rows, o.tolerance);
      EXPECT_EQ(fit.surface.periodic_u, c.cu);
      EXPECT_EQ(fit.surface.periodic_v, c.cv);
      FitOptions o1 = o;
      o1.method = FitMethod::kSfit01;
      EXPECT_LE(size_of(fit), size_of(fit_surface(rows, o1)));
      expect_minimal(fit, rows, o);
    }
}

TEST(SurfaceSearch, ZeroToleranceInterpolates) {
  const Rows rows = test::sample_rows(smooth_height, {9, 12, 10, 11, 9, 13});
  FitOptions o;  // T = 0
  const FitResult fit = fit_surface(rows, o);
  EXPECT_TRUE(fit.report.within_tolerance);
  EXPECT_LE(test::reference_deviation(fit, rows).maxCoeff(), fit.report.roundoff);
}

TEST(SurfaceSearch, SameResultForAnyThreadCount) {
  // Above the 20000 points below which a fit runs on one thread.
  const Rows rows = test::sample_rows(smooth_height, std::vector<int>(110, 200));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  o.threads = 1;
  const FitResult one = fit_surface(rows, o);
  o.threads = 3;
  const FitResult three = fit_surface(rows, o);
  test::expect_same_surface(one, three);
  EXPECT_EQ(one.report.stop_reason, three.report.stop_reason);
}

TEST(SurfaceSearch, IncrementalFitRefitsInFullAndMatches) {
  const Rows rows = test::sample_rows(smooth_height, {20, 24, 22, 21, 25, 23, 20, 22});
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  IncrementalFit inc(rows, o);
  inc.move_point(3, 5, inc.rows()[3][5] + Point(0, 0, 0.05));
  EXPECT_EQ(inc.rows_refitted(), rows.size());
  test::expect_same_surface(inc.result(), fit_surface(inc.rows(), o));
}

TEST(SurfaceSearch, FixedCountsFitExactlyThereAndSayWhetherTheyHold) {
  const Rows rows = test::sample_rows(smooth_height, std::vector<int>(30, 30));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-2);
  const FitResult best = fit_surface(rows, o);
  ASSERT_EQ(best.report.method, FitMethod::kSurface);
  o.parametrization = best.report.parametrization;
  o.norm = best.report.norm;
  o.counts = std::array<int, 2>{best.surface.count_u, best.surface.count_v};
  const FitResult again = fit_surface(rows, o);
  test::expect_same_surface(again, best);
  EXPECT_TRUE(again.report.within_tolerance);
  EXPECT_EQ(again.report.stop_reason, "counts given");
  o.counts = std::array<int, 2>{4, 4};
  EXPECT_FALSE(fit_surface(rows, o).report.within_tolerance);
  o.counts = std::array<int, 2>{3, 4};  // below degree + 1
  EXPECT_THROW(fit_surface(rows, o), Error);
}

TEST(SurfaceSearch, MinimaxOfALineToAParabolaEquioscillatesAtOneEighth) {
  // z = x^2 on [0, 1] by a line (degree 1, 2 control points along u): the minimax line is
  // x - 1/8, its error +-1/8 at x = 0, 1/2, 1 (Chebyshev equioscillation); least squares'
  // is larger (1/6 at the ends for dense points).
  Rows rows;
  for (int j = 0; j < 3; ++j) {
    std::vector<Point> row;
    for (int k = 0; k <= 40; ++k) row.emplace_back(k / 40.0, j, (k / 40.0) * (k / 40.0));
    rows.add_row(row);
  }
  FitOptions o;
  o.degree_u = 1;
  o.degree_v = 1;
  o.parametrization = Parametrization::kUniform;
  o.tolerance = Point(1, 1, 0.14);  // least squares misses it by under 25 %
  o.counts = std::array<int, 2>{2, 2};
  o.norm = FitNorm::kLinf;
  const FitResult linf = fit_surface(rows, o);
  EXPECT_TRUE(linf.report.within_tolerance);
  EXPECT_EQ(linf.report.norm, FitNorm::kLinf);
  EXPECT_NEAR(linf.report.max_deviation.z(), 0.125, 1e-9);
  o.norm = FitNorm::kL2;
  const FitResult l2 = fit_surface(rows, o);
  EXPECT_GT(l2.report.max_deviation.z(), 0.15);
  EXPECT_FALSE(l2.report.within_tolerance);
  // Where least squares misses T by a little, the search's auto norm takes the minimax fit.
  o.norm = FitNorm::kAuto;
  const FitResult automatic = fit_surface(rows, o);
  EXPECT_EQ(automatic.report.norm, FitNorm::kLinf);
  EXPECT_TRUE(automatic.report.within_tolerance);
}

// The same at sizes 1e100 and 1e-100 (the accepted range of coordinates): the LP works in
// units of a power of two near the residuals, so its answer is the unit case's times the size
// (before, CLP aborted the process on bounds beyond 1e100).
TEST(SurfaceSearch, MinimaxIsScaleFree) {
  for (double size : {1e100, 1e-100}) {
    Rows rows;
    for (int j = 0; j < 3; ++j) {
      std::vector<Point> row;
      for (int k = 0; k <= 40; ++k)
        row.emplace_back(size * k / 40.0, size * j, size * (k / 40.0) * (k / 40.0));
      rows.add_row(row);
    }
    FitOptions o;
    o.degree_u = 1;
    o.degree_v = 1;
    o.parametrization = Parametrization::kUniform;
    o.tolerance = size * Point(1, 1, 0.14);
    o.counts = std::array<int, 2>{2, 2};
    o.norm = FitNorm::kLinf;
    const FitResult linf = fit_surface(rows, o);
    EXPECT_TRUE(linf.report.within_tolerance) << size;
    EXPECT_NEAR(linf.report.max_deviation.z() / size, 0.125, 1e-9) << size;
  }
}

TEST(SurfaceSearch, NamesOfMethodsAndNormsRoundTrip) {
  for (FitMethod m : {FitMethod::kSurface, FitMethod::kSfit01}) {
    FitMethod back{};
    ASSERT_TRUE(parse_fit_method(to_string(m), back));
    EXPECT_EQ(back, m);
  }
  for (FitNorm n : {FitNorm::kL2, FitNorm::kLinf, FitNorm::kAuto}) {
    FitNorm back{};
    ASSERT_TRUE(parse_fit_norm(to_string(n), back));
    EXPECT_EQ(back, n);
  }
  FitMethod m;
  EXPECT_FALSE(parse_fit_method("fewest", m));
}

}  // namespace
}  // namespace sfit
