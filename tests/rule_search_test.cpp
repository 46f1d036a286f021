// The default's rule search (FitOptions::parametrization kAuto, method kSurface): it keeps the
// fewest control points of every rule it tries, whatever the per-axis tolerances and however
// few the rows.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

constexpr Parametrization kRules[] = {Parametrization::kGeometric, Parametrization::kUniform,
                                      Parametrization::kChord, Parametrization::kCentripetal,
                                      Parametrization::kPaper};

using test::size_of;

// The default against each rule alone: never more control points, every point within T.
void expect_fewest(const Rows& rows, const Point& tol, const char* what) {
  FitOptions o;
  o.tolerance = tol;
  const FitResult d = fit_surface(rows, o);
  ASSERT_TRUE(d.report.within_tolerance) << what;
  const Point dev = test::reference_deviation(d, rows);
  for (int a = 0; a < 3; ++a) EXPECT_LE(dev[a], tol[a] * (1 + 1e-9)) << what << " axis " << a;
  // The four row rules, and the geometric one last where the rows are enough for it (and a
  // row rule did not already reach the smallest pair there is).
  const std::size_t searched = d.report.rules_searched.size();
  EXPECT_TRUE(searched == 4u ||
              (searched == 5u && d.report.rules_searched[4] == Parametrization::kGeometric))
      << what;
  for (Parametrization rule : kRules) {
    FitOptions r = o;
    r.parametrization = rule;
    const FitResult f = fit_surface(rows, r);
    std::printf("[ measured ] %s: %s alone %d x %d, default %d x %d (%s)\n", what,
                std::string(to_string(rule)).c_str(), f.surface.count_u, f.surface.count_v,
                d.surface.count_u, d.surface.count_v,
                std::string(to_string(d.report.parametrization)).c_str());
    if (f.report.within_tolerance) {
      EXPECT_LE(size_of(d), size_of(f)) << what << ": " << to_string(rule);
    }
  }
}

TEST(RuleSearch, HeightGridWithATightPlaneAndALooseHeight) {
  // 100 x 100 heights on a unit grid, T = (0.001, 0.001, 0.5): x and y are exact under the
  // uniform rule, z has half a unit. The search's distance check once used min T = 0.001 on
  // every axis, so nothing below the two stages' 44 x 41 held; uniform alone gave 13 x 13.
  std::vector<int> counts(100, 100);
  const Rows rows = test::sample_rows(
      [](double s, double t) {
        const double x = 99 * s, y = 99 * t;
        return Point(x, y, 20 * std::sin(x / 12) * std::cos(y / 15) + 4 * std::sin(x / 5 + y / 7));
      },
      counts);
  expect_fewest(rows, Point(0.001, 0.001, 0.5), "height grid");
}

TEST(RuleSearch, ThreeRowsTryEveryRule) {
  // Fewer rows than degree_v + 1: the search fits at degree 2 across and raises it to 3.
  std::vector<int> counts = {400, 400, 400};
  const Rows rows = test::sample_rows(
      [](double s, double t) {
        const double a = 2 * 3.14159265358979 * s;
        return Point((2 + t) * std::cos(a), (1 + 0.5 * t) * std::sin(a) + 0.2 * std::sin(5 * a),
                     3 * t + 0.1 * std::cos(3 * a));
      },
      counts);
  const Point tol = Point::Constant(1e-3);
  expect_fewest(rows, tol, "three rows");
  FitOptions o;
  o.tolerance = tol;
  const FitResult d = fit_surface(rows, o);
  EXPECT_EQ(d.report.method, FitMethod::kSurface) << d.report.stop_reason;
  EXPECT_EQ(d.surface.degree_v, 3);
  EXPECT_EQ(d.surface.count_v, 4);

  // The CLI's line names the rules it searched and the one that won.
  const std::string dir = test::temp_dir(), in = dir + "/three.rows";
  std::string text;
  char line[128];
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (const Point& p : rows[j]) {
      std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p.x(), p.y(), p.z());
      text += line;
    }
    text += "\n";
  }
  test::write_file(in, text);
  const test::Run run = test::run_cli("fit '" + in + "' --tol 0.001");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find(std::string(to_string(d.report.parametrization)) +
                         " parameters gave the fewest control points of the rules searched "
                         "(uniform, chord, centripetal, paper)"),
            std::string::npos)
      << run.err;
}

}  // namespace
}  // namespace sfit
