#include "exchange_cases.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "test_support.h"

namespace sfit::test {

double surface_diagonal(const Surface& s, int n) {
  Point lo = Point::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const Point p = s.evaluate(s.u_end() * a / (n - 1), s.v_end() * b / (n - 1));
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  return (hi - lo).norm();
}

namespace {

FittedCase fit_case(std::string name, Rows rows, bool cu, bool cv, bool bundled) {
  FittedCase c;
  c.name = std::move(name);
  c.closed_u = cu;
  c.closed_v = cv;
  c.bundled = bundled;
  c.rows = std::move(rows);
  FitOptions o;
  o.closed_u = cu;
  o.closed_v = cv;
  o.tolerance = relative_tolerance(c.rows, 1e-3);
  c.fit = fit_surface(c.rows, o);
  c.diagonal = surface_diagonal(c.fit.surface);
  return c;
}

// The bundled and synthetic cases, fitted on first use.
const std::vector<FittedCase>& bundled_cases() {
  static const std::vector<FittedCase> cases = [] {
    std::vector<FittedCase> v;
    v.push_back(fit_case("ship_px121_stations", load_rows(example("ship_px121_stations.rows")),
                         false, false, true));
    v.push_back(fit_case("d150_wing", load_rows(example("d150_wing.rows")), true, false, true));
    v.push_back(fit_case("iea3p4mw_blade_ragged9",
                         load_rows(example("iea3p4mw_blade_ragged9.rows")), true, false, true));
    // Closed sequence of open rows: generators of a wavy tube.
    const double pi = std::numbers::pi;
    v.push_back(fit_case("tube_closed_v",
                         sample_rows(
                             [&](double s, double t) {
                               const double a = 2 * pi * t,
                                            r = 1 + 0.2 * std::sin(3 * a) + 0.3 * s * s;
                               return Point(r * std::cos(a), r * std::sin(a), 4 * s);
                             },
                             std::vector<int>(12, 15), false, true),
                         false, true, true));
    v.push_back(fit_case("torus_closed_uv",
                         sample_rows(
                             [&](double s, double t) {
                               const double a = 2 * pi * s, b = 2 * pi * t;
                               const double r = 0.5 + 0.1 * std::cos(2 * b);
                               return Point((2 + r * std::cos(a)) * std::cos(b),
                                            (2 + r * std::cos(a)) * std::sin(b), r * std::sin(a));
                             },
                             std::vector<int>(16, 20), true, true),
                         true, true, true));
    return v;
  }();
  return cases;
}

}  // namespace

const std::vector<FittedCase>& fitted_cases(std::vector<std::string>* missing) {
  static std::vector<std::string> absent;
  static const std::vector<FittedCase> cases = [] {
    std::vector<FittedCase> v = bundled_cases();
    const std::vector<std::pair<std::string, bool>> more = {
        {"ring_body", true},           {"bent_tube", true},
        {"spout_tube", true},          {"iea15mw_blade_af50", true},
        {"height_field_small", false}, {"height_field", false},
        {"topobathy", false},          {"iea3p4mw_blade_ragged9", true},
        {"d150_wing", true},           {"ship_px121_stations", false}};
    for (const auto& [name, cu] : more)
      v.push_back(fit_case("data/" + name, load_rows(example(name + ".rows")), cu, false, false));
    return v;
  }();
  if (missing) *missing = absent;
  return cases;
}

std::vector<const FittedCase*> must_pass_cases() {
  std::vector<const FittedCase*> v;
  for (const auto& c : bundled_cases()) v.push_back(&c);
  return v;
}

}  // namespace sfit::test
