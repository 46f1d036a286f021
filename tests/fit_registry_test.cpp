// The fit driver and its registries (src/core/fit/fit_driver.h, fit_registry.h): a method and a
// parameter rule registered here through the public face (sfit/fit_registry.h), in the test
// only, are selected through FitOptions by name,
// fitted by fit_surface(), checked by the driver's final check, listed by the option table while
// registered; validation runs once per fit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "fit_driver.h"
#include "fit_registry.h"
#include "sfit/error.h"
#include "sfit/fit_registry.h"
#include "sfit/options.h"
#include "sfit/surface_fit.h"
#include "support/test_support.h"

namespace sfit {
namespace {

// A bilinear patch through four corners: the fake method's surface is exact on it.
const Point kCorner[4] = {{0, 0, 0}, {2, 0, 0.5}, {0, 1, -0.25}, {2, 1.5, 1}};
Point bilinear(double s, double t) {
  return (1 - s) * (1 - t) * kCorner[0] + s * (1 - t) * kCorner[1] + (1 - s) * t * kCorner[2] +
         s * t * kCorner[3];
}

// The fake method: the bilinear surface through the rows' corner points (degree 1 x 1, 2 x 2
// control points), u uniform along each row, v uniform across; it claims to hold T (the
// driver's final check decides). Counts its calls and what it was given.
struct FakeLog {
  int calls = 0;
  Point centre = Point::Zero();
  std::size_t centred_points = 0;
};

FitResult corners_surface(const MethodInput& spec, FakeLog& log) {
  ++log.calls;
  log.centre = spec.centre;
  log.centred_points = spec.centred.total_points();
  const Rows& rows = spec.rows;
  FitResult r;
  Surface& s = r.surface;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  const auto first = rows[0], last = rows[rows.size() - 1];
  s.control = {first.front(), last.front(), first.back(), last.back()};  // P_ij, i along u
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const std::size_t n = rows[j].size();
    for (std::size_t k = 0; k < n; ++k) r.u.push_back(static_cast<double>(k) / (n - 1));
    r.v.push_back(static_cast<double>(j) / (rows.size() - 1));
  }
  r.report.points = rows.total_points();
  r.report.rows = rows.size();
  r.report.tolerance = spec.options.tolerance;
  r.report.count_u = r.report.count_v = 2;
  r.report.degree_u = r.report.degree_v = 1;
  r.report.method = spec.options.method;
  r.report.within_tolerance = true;  // the claim
  return r;
}

Rows rows_of(const std::function<Point(double, double)>& f) {
  return test::sample_rows(f, {9, 11, 7, 10, 9, 8});
}

FitOptions options_with_tolerance(double t) {
  FitOptions o;
  o.tolerance = Point::Constant(t);
  return o;
}

TEST(FitRegistry, FakeMethodSelectedByNameRunsUnderTheDriver) {
  FakeLog log;
  const RegisteredMethod fake("corners_test", "the bilinear patch through the corners",
                              [&](const MethodInput& s) { return corners_surface(s, log); });
  FitSettings st;
  set_fit_option(st, "method", std::string("corners_test"), "method");
  EXPECT_EQ(st.options.method, fake.id());
  EXPECT_EQ(to_string(fake.id()), "corners_test");

  const Rows rows = rows_of(bilinear);
  FitOptions o = st.options;
  o.tolerance = Point::Constant(1e-9);
  const FitResult r = fit_surface(rows, o);
  EXPECT_EQ(log.calls, 1);
  EXPECT_EQ(r.report.method, fake.id());
  EXPECT_EQ(r.surface.count_u * r.surface.count_v, 4);
  EXPECT_TRUE(r.report.within_tolerance);  // the final check agrees: the data is bilinear
  EXPECT_LT(r.report.max_deviation.maxCoeff(), 1e-12);
  // The method got the rows centred once, by the driver: the box's centre.
  const BoundingBox box = bounding_box(rows);
  EXPECT_EQ(log.centre, 0.5 * (box.min + box.max));
  EXPECT_EQ(log.centred_points, rows.total_points());
}

TEST(FitRegistry, DriversFinalCheckRejectsAFakeMethodsBadSurface) {
  FakeLog log;
  const RegisteredMethod fake("corners_test", "",
                              [&](const MethodInput& s) { return corners_surface(s, log); });
  // Not bilinear: the corners' patch misses the middle by up to 0.3, far beyond T.
  const Rows rows = rows_of([](double s, double t) {
    Point p = bilinear(s, t);
    p.z() += 0.3 * std::sin(M_PI * s) * std::sin(M_PI * t);
    return p;
  });
  FitOptions o = options_with_tolerance(1e-3);
  o.method = fake.id();
  const FitResult r = fit_surface(rows, o);
  EXPECT_EQ(log.calls, 1);
  EXPECT_FALSE(r.report.within_tolerance);  // the claim was true; the driver's check is not
  EXPECT_NEAR(r.report.max_deviation.z(), 0.3 * std::sin(M_PI * 0.5) * std::sin(M_PI * 0.4), 0.05);
  // The independent evaluator agrees that it misses.
  EXPECT_GT(test::reference_deviation(r, rows).z(), 0.2);
}

TEST(FitRegistry, FakeMethodNeverSeesInvalidRows) {
  FakeLog log;
  const RegisteredMethod fake("corners_test", "",
                              [&](const MethodInput& s) { return corners_surface(s, log); });
  FitOptions o = options_with_tolerance(1e-3);
  o.method = fake.id();
  const Rows one = test::sample_rows(bilinear, {5});
  try {
    fit_surface(one, o);
    FAIL() << "one row was fitted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputData);
  }
  EXPECT_EQ(log.calls, 0);
}

TEST(FitRegistry, UnregisteredMethodIdIsAUsageError) {
  FitMethod gone;
  {
    const RegisteredMethod fake("corners_test", "", [](const MethodInput&) { return FitResult{}; });
    gone = fake.id();
  }
  FitOptions o = options_with_tolerance(1e-3);
  o.method = gone;
  try {
    fit_surface(rows_of(bilinear), o);
    FAIL() << "an unregistered method ran";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kUsage);
    EXPECT_NE(std::string(e.what()).find("surface, sfit01"), std::string::npos) << e.what();
  }
  FitSettings st;
  EXPECT_THROW(set_fit_option(st, "method", std::string("corners_test"), "method"), Error);
}

// The fake rule: u = the square of the uniform rule's position.
std::vector<double> squared(std::span<const Point> points, bool periodic) {
  std::vector<double> f(points.size());
  const double steps = static_cast<double>(periodic ? points.size() : points.size() - 1);
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = std::pow(k / steps, 2);
  return f;
}

// Points (and rows) crowd at the start as the squared rule expects them.
Rows crowded_rows() {
  Rows rows;
  for (int j = 0; j < 7; ++j) {
    std::vector<Point> row;
    const int n = 12 + j % 3;
    for (int k = 0; k < n; ++k) {
      const double s = std::pow(static_cast<double>(k) / (n - 1), 2), t = std::pow(j / 6.0, 2);
      row.push_back({s, t, 0.2 * std::sin(2 * s + t) + 0.1 * s * t});
    }
    rows.add_row(row);
  }
  return rows;
}

TEST(FitRegistry, FakeRuleSelectedByNameGivesTheRowsItsPositions) {
  const RegisteredRule rule("squared_test", "the uniform position squared", squared);
  FitSettings st;
  set_fit_option(st, "parameters", std::string("squared_test"), "parameters");
  EXPECT_EQ(st.options.parametrization, rule.id());
  EXPECT_EQ(to_string(rule.id()), "squared_test");
  const Rows rows = crowded_rows();
  for (FitMethod m : {FitMethod::kSurface, FitMethod::kSfit01}) {
    FitOptions o = st.options;
    o.tolerance = Point::Constant(1e-4);
    o.method = m;
    const FitResult r = fit_surface(rows, o);
    EXPECT_TRUE(r.report.within_tolerance) << to_string(m);
    EXPECT_EQ(r.report.parametrization, rule.id()) << to_string(m);
    // Row 0's u are at the squared positions (scaled onto the domain).
    const std::size_t n = rows[0].size();
    for (std::size_t k = 0; k < n; ++k)
      EXPECT_NEAR(r.u[k] / r.u[n - 1], std::pow(k / double(n - 1), 2), 1e-12) << to_string(m);
    EXPECT_LE(test::reference_deviation(r, rows).maxCoeff(), 1e-4 * (1 + 1e-9));
  }
}

TEST(FitRegistry, FakeRuleGivingBadPositionsIsAUsageError) {
  const RegisteredRule rule("reversed_test", "", [](std::span<const Point> p, bool) {
    std::vector<double> f(p.size());
    for (std::size_t k = 0; k < f.size(); ++k) f[k] = 1.0 - k / double(f.size() - 1);
    return f;
  });
  FitOptions o = options_with_tolerance(1e-3);
  o.parametrization = rule.id();
  o.method = FitMethod::kSfit01;
  try {
    fit_surface(crowded_rows(), o);
    FAIL() << "decreasing positions were fitted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kUsage);
    EXPECT_EQ(e.place().option, "parameters");
  }
}

bool lists(const OptionSpec* s, std::string_view name) {
  return std::find(s->choices.begin(), s->choices.end(), name) != s->choices.end() &&
         s->help.find(std::string(name)) != std::string::npos;
}

TEST(FitRegistry, OptionTableListsRegisteredNamesWhileRegistered) {
  EXPECT_TRUE(lists(find_option("method"), "surface"));
  EXPECT_TRUE(lists(find_option("method"), "sfit01"));
  EXPECT_TRUE(lists(find_option("parameters"), "chord"));
  {
    const RegisteredMethod fake("corners_test", "bilinear through the corners",
                                [](const MethodInput&) { return FitResult{}; });
    const RegisteredRule rule("squared_test", "uniform squared", squared);
    EXPECT_TRUE(lists(find_option("method"), "corners_test"));
    EXPECT_NE(find_option("method")->help.find("bilinear through the corners"), std::string::npos);
    EXPECT_TRUE(lists(find_option("parameters"), "squared_test"));
    EXPECT_NE(option_table_markdown().find("squared_test"), std::string::npos);
    Parametrization p;
    EXPECT_TRUE(parse_parametrization("squared_test", p));
    EXPECT_EQ(p, rule.id());
  }
  EXPECT_FALSE(lists(find_option("method"), "corners_test"));
  EXPECT_FALSE(lists(find_option("parameters"), "squared_test"));
  Parametrization p;
  EXPECT_FALSE(parse_parametrization("squared_test", p));
  // The built-ins' text is what it was before the registries (docs/options.md is generated
  // from it and compared).
  EXPECT_EQ(find_option("method")->help,
            "surface (the fewest nu x nv whose surface holds T, searched over all points at once; "
            "never more than sfit01) or sfit01 (the paper's two stages)");
}

TEST(FitRegistry, NameTakenIsRefused) {
  EXPECT_THROW(RegisteredMethod("sfit01", "", [](const MethodInput&) { return FitResult{}; }),
               Error);
  EXPECT_THROW(RegisteredRule("chord", "", squared), Error);
}

TEST(FitDriver, ValidatesOncePerFit) {
  // Open rows, closed rows whose seams the driver aligns, each method, a fixed pair.
  const Rows open = rows_of(
      [](double s, double t) { return Point(s, t, 0.1 * std::sin(3 * s) * std::cos(2 * t)); });
  const Rows tube = test::sample_rows(
      [](double s, double t) {
        const double a = 2 * M_PI * (s + 0.13 * std::round(6 * t));  // rows start at turned seams
        return Point(std::cos(a), std::sin(a), 2 * t);
      },
      {16, 16, 16, 16, 16, 16, 16}, true);
  struct Case {
    const Rows* rows;
    bool closed;
    FitMethod method;
    bool counts;
  };
  for (const Case& c :
       {Case{&open, false, FitMethod::kSurface, false},
        Case{&open, false, FitMethod::kSfit01, false},
        Case{&tube, true, FitMethod::kSurface, false}, Case{&tube, true, FitMethod::kSfit01, false},
        Case{&open, false, FitMethod::kSurface, true}}) {
    FitOptions o = options_with_tolerance(1e-3);
    o.closed_u = c.closed;
    o.method = c.method;
    if (c.counts) o.counts = std::array<int, 2>{5, 5};
    const long before = detail::validations();
    const FitResult r = fit_surface(*c.rows, o);
    EXPECT_EQ(detail::validations() - before, 1)
        << to_string(c.method) << (c.closed ? " closed" : " open") << (c.counts ? " counts" : "");
    if (c.closed) {
      ASSERT_EQ(r.report.seams.size(), tube.size());  // the driver aligned them
    }
  }
}

}  // namespace
}  // namespace sfit
