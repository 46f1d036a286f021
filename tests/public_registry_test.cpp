// Plug-ins registered as an application registers them: through the public headers only
// (sfit/fit_registry.h; this test has no private include path and no test support). A method
// and a row rule are selected by name through the option table, run under the fit driver and
// checked by it; their handles unregister them; taken names are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "sfit/error.h"
#include "sfit/fit_registry.h"
#include "sfit/options.h"
#include "sfit/surface_fit.h"

namespace sfit {
namespace {

// A bilinear patch through four corners, and rows sampled on it (ragged, uneven).
const Point kCorner[4] = {{0, 0, 0}, {2, 0, 0.5}, {0, 1, -0.25}, {2, 1.5, 1}};
Point bilinear(double s, double t) {
  return (1 - s) * (1 - t) * kCorner[0] + s * (1 - t) * kCorner[1] + (1 - s) * t * kCorner[2] +
         s * t * kCorner[3];
}

Rows sample(double bump) {
  Rows rows;
  const int sizes[] = {9, 11, 7, 10, 9, 8};
  for (int j = 0; j < 6; ++j) {
    std::vector<Point> row;
    for (int k = 0; k < sizes[j]; ++k) {
      const double s = static_cast<double>(k) / (sizes[j] - 1), t = j / 5.0;
      Point p = bilinear(s, t);
      p.z() += bump * std::sin(M_PI * s) * std::sin(M_PI * t);
      row.push_back(p);
    }
    rows.add_row(row);
  }
  return rows;
}

// The application's method: the bilinear patch through the rows' corner points, u uniform
// along each row, v uniform across; it claims to hold T. Records what the driver gave it.
struct Seen {
  int calls = 0;
  Point centre = Point::Constant(NAN);
  double centred_error = NAN;  // the largest |centred - (rows - centre)|
  bool options_aligned = false;
};

FitResult corners(const MethodInput& in, Seen& seen) {
  ++seen.calls;
  seen.centre = in.centre;
  seen.centred_error = 0;
  for (std::size_t j = 0; j < in.rows.size(); ++j)
    for (std::size_t k = 0; k < in.rows[j].size(); ++k)
      seen.centred_error =
          std::max(seen.centred_error,
                   (in.centred[j][k] - (in.rows[j][k] - in.centre)).cwiseAbs().maxCoeff());
  seen.options_aligned =
      in.options.seam == SeamMode::kKeep && in.options.orient == OrientMode::kKeep;
  const Rows& rows = in.rows;
  FitResult r;
  Surface& s = r.surface;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  const auto first = rows[0], last = rows[rows.size() - 1];
  s.control = {first.front(), last.front(), first.back(), last.back()};
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const std::size_t n = rows[j].size();
    for (std::size_t k = 0; k < n; ++k) r.u.push_back(static_cast<double>(k) / (n - 1));
    r.v.push_back(static_cast<double>(j) / (rows.size() - 1));
  }
  r.report.points = rows.total_points();
  r.report.rows = rows.size();
  r.report.tolerance = in.options.tolerance;
  r.report.count_u = r.report.count_v = 2;
  r.report.degree_u = r.report.degree_v = 1;
  r.report.method = in.options.method;
  r.report.within_tolerance = true;  // the claim; the driver's final check decides
  return r;
}

// The largest per-axis distance of a point from the surface at its (u, v), evaluated here.
double worst(const FitResult& r, const Rows& rows) {
  double w = 0;
  std::size_t i = 0;
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (std::size_t k = 0; k < rows[j].size(); ++k, ++i)
      w = std::max(w, (r.surface.evaluate(r.u[i], r.v[j]) - rows[j][k]).cwiseAbs().maxCoeff());
  return w;
}

TEST(PublicRegistry, MethodSelectedByNameRunsUnderTheDriver) {
  Seen seen;
  const RegisteredMethod m("corners_app", "the bilinear patch through the corners",
                           [&](const MethodInput& in) { return corners(in, seen); });
  FitSettings st;
  set_fit_option(st, "method", std::string("corners_app"), "method");
  EXPECT_EQ(st.options.method, m.id());
  EXPECT_EQ(to_string(m.id()), "corners_app");
  EXPECT_NE(find_option("method")->help.find("the bilinear patch through the corners"),
            std::string::npos);

  const Rows rows = sample(0);
  FitOptions o = st.options;
  o.tolerance = Point::Constant(1e-9);
  const FitResult r = fit_surface(rows, o);
  EXPECT_EQ(seen.calls, 1);
  EXPECT_EQ(r.report.method, m.id());
  EXPECT_EQ(r.surface.count_u * r.surface.count_v, 4);
  EXPECT_TRUE(r.report.within_tolerance);
  EXPECT_LT(worst(r, rows), 1e-12);
  const BoundingBox box = bounding_box(rows);
  EXPECT_EQ(seen.centre, 0.5 * (box.min + box.max));
  EXPECT_EQ(seen.centred_error, 0);
  EXPECT_TRUE(seen.options_aligned);
}

TEST(PublicRegistry, DriverRejectsTheMethodsFalseClaim) {
  Seen seen;
  const RegisteredMethod m("corners_app", "",
                           [&](const MethodInput& in) { return corners(in, seen); });
  const Rows rows = sample(0.3);  // the corners' patch misses the middle by about 0.3
  FitOptions o;
  o.tolerance = Point::Constant(1e-3);
  o.method = m.id();
  const FitResult r = fit_surface(rows, o);
  EXPECT_EQ(seen.calls, 1);
  EXPECT_FALSE(r.report.within_tolerance);
  EXPECT_GT(worst(r, rows), 0.2);
  EXPECT_GT(r.report.max_deviation.z(), 0.2);
}

// The application's rule: u = the square of the uniform position.
std::vector<double> squared(std::span<const Point> points, bool periodic) {
  std::vector<double> f(points.size());
  const double steps = static_cast<double>(periodic ? points.size() : points.size() - 1);
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = std::pow(k / steps, 2);
  return f;
}

TEST(PublicRegistry, RuleSelectedByNameGivesTheRowsItsPositions) {
  const RegisteredRule rule("squared_app", "the uniform position squared", squared);
  FitSettings st;
  set_fit_option(st, "parameters", std::string("squared_app"), "parameters");
  EXPECT_EQ(st.options.parametrization, rule.id());
  Rows rows;  // points crowd at the start as the rule expects
  for (int j = 0; j < 7; ++j) {
    std::vector<Point> row;
    const int n = 12 + j % 3;
    for (int k = 0; k < n; ++k) {
      const double s = std::pow(static_cast<double>(k) / (n - 1), 2), t = std::pow(j / 6.0, 2);
      row.push_back({s, t, 0.2 * std::sin(2 * s + t) + 0.1 * s * t});
    }
    rows.add_row(row);
  }
  for (FitMethod method : {FitMethod::kSurface, FitMethod::kSfit01}) {
    FitOptions o = st.options;
    o.tolerance = Point::Constant(1e-4);
    o.method = method;
    const FitResult r = fit_surface(rows, o);
    EXPECT_TRUE(r.report.within_tolerance) << to_string(method);
    EXPECT_EQ(r.report.parametrization, rule.id()) << to_string(method);
    const std::size_t n = rows[0].size();
    for (std::size_t k = 0; k < n; ++k)
      EXPECT_NEAR(r.u[k] / r.u[n - 1], std::pow(k / double(n - 1), 2), 1e-12);
    EXPECT_LE(worst(r, rows), 1e-4 * (1 + 1e-9)) << to_string(method);
  }
}

// Rows on which the squared rule is the surface's own parameter: the surface is a bicubic
// polynomial in (s, t), x = s + s^2 / 2 (so no plane projection, chord length or index gives
// s), and row j's points are at s = (k / (n - 1))^2, t = (j / 8)^2, the squared positions along
// the rows and across them. At the squared rule one span fits it to round-off (4 x 4 control
// points); every built-in rule needs more at this T.
Rows squared_rows() {
  Rows rows;
  for (int j = 0; j < 9; ++j) {
    std::vector<Point> row;
    const int n = 14 + j % 3;
    for (int k = 0; k < n; ++k) {
      const double s = std::pow(static_cast<double>(k) / (n - 1), 2), t = std::pow(j / 8.0, 2);
      row.push_back({s + 0.5 * s * s, t, s * s * s - s * t + 0.3 * t * t + 0.2 * s * t * t});
    }
    rows.add_row(row);
  }
  return rows;
}

TEST(PublicRegistry, OptedInRuleIsTriedByTheAutomaticChoices) {
  const Rows rows = squared_rows();
  FitOptions o;
  o.tolerance = Point::Constant(1e-7);
  const auto size = [](const FitResult& r) { return r.surface.count_u * r.surface.count_v; };
  // Not registered: the built-ins' best.
  const FitResult builtin = fit_surface(rows, o);
  ASSERT_TRUE(builtin.report.within_tolerance);
  EXPECT_GT(size(builtin), 16);
  {
    // Registered to be used when named only: the default and `fewest` do not try it.
    const RegisteredRule rule("squared_named_app", "", squared);
    for (Parametrization choice : {Parametrization::kAuto, Parametrization::kFewest}) {
      FitOptions oc = o;
      oc.parametrization = choice;
      const FitResult r = fit_surface(rows, oc);
      EXPECT_NE(r.report.parametrization, rule.id()) << to_string(choice);
      EXPECT_EQ(size(r), size(builtin)) << to_string(choice);
    }
    FitOptions named = o;
    named.parametrization = rule.id();
    EXPECT_EQ(size(fit_surface(rows, named)), 16);  // it would have won
  }
  // Opted in: the default (auto), `fewest`, and the two stages' `fewest` choose it.
  const RegisteredRule rule("squared_auto_app", "", squared, RuleUse::kAlsoAuto);
  for (FitMethod method : {FitMethod::kSurface, FitMethod::kSfit01}) {
    for (Parametrization choice : {Parametrization::kAuto, Parametrization::kFewest}) {
      if (method == FitMethod::kSfit01 && choice == Parametrization::kAuto) continue;  // paper
      FitOptions oc = o;
      oc.method = method;
      oc.parametrization = choice;
      const FitResult r = fit_surface(rows, oc);
      EXPECT_TRUE(r.report.within_tolerance) << to_string(method) << " " << to_string(choice);
      EXPECT_EQ(r.report.parametrization, rule.id())
          << to_string(method) << " " << to_string(choice) << ": "
          << to_string(r.report.parametrization);
      EXPECT_EQ(size(r), 16) << to_string(method) << " " << to_string(choice);
      EXPECT_LE(worst(r, rows), 1e-7 * (1 + 1e-9));
    }
  }
  // The two stages' auto is the paper's rule, opted-in rules or not.
  FitOptions paper = o;
  paper.method = FitMethod::kSfit01;
  EXPECT_EQ(fit_surface(rows, paper).report.parametrization, Parametrization::kPaper);
}

TEST(PublicRegistry, HandlesUnregisterAndMoveTheRegistration) {
  FitMethod id{};
  {
    RegisteredMethod a("moved_app", "", [](const MethodInput&) { return FitResult{}; });
    id = a.id();
    RegisteredMethod b = std::move(a);  // the registration moves; `a` no longer owns it
    EXPECT_EQ(b.id(), id);
    FitSettings st;
    set_fit_option(st, "method", std::string("moved_app"), "method");
    EXPECT_EQ(st.options.method, id);
    RegisteredRule r("moved_rule_app", "", squared);
    RegisteredRule r2 = std::move(r);
    set_fit_option(st, "parameters", std::string("moved_rule_app"), "parameters");
    EXPECT_EQ(st.options.parametrization, r2.id());
  }
  FitSettings st;
  try {
    set_fit_option(st, "method", std::string("moved_app"), "method");
    FAIL() << "an unregistered method was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kUsage);
  }
  EXPECT_THROW(set_fit_option(st, "parameters", std::string("moved_rule_app"), "parameters"),
               Error);
  FitOptions o;
  o.method = id;
  try {
    fit_surface(sample(0), o);
    FAIL() << "an unregistered method ran";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kUsage);
  }
  // The name is free again.
  const RegisteredMethod again("moved_app", "", [](const MethodInput&) { return FitResult{}; });
  EXPECT_NE(again.id(), FitMethod::kSurface);
}

TEST(PublicRegistry, TakenOrEmptyNamesAreRefused) {
  for (const char* name : {"surface", "sfit01", ""}) {
    try {
      RegisteredMethod m(name, "", [](const MethodInput&) { return FitResult{}; });
      FAIL() << "registered as \"" << name << "\"";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kUsage);
    }
  }
  const RegisteredRule mine("taken_app", "", squared);
  EXPECT_THROW(RegisteredRule("taken_app", "", squared), Error);
  EXPECT_THROW(RegisteredRule("chord", "", squared), Error);
}

}  // namespace
}  // namespace sfit
