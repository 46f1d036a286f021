// --knots adaptive: knots where the shape needs them. On generated sections with sharp corners
// and on a sheet with one local bump the adaptive fit needs at least 30% fewer control points
// than the uniform one; on every set it never needs more; every point holds T (an independent
// evaluation of the written surface), and nothing folds.
#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_pair.h"
#include "reference_eval.h"
#include "sfit/fold_check.h"
#include "sfit/io/report_json.h"
#include "sfit/io/surface_json.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

// Hull-like stations: a flat-ish bottom, a sharp chine, a side, a sharp deck corner and a deck;
// the beam and depth change along the hull; `moving` shifts where the corners fall.
Rows box_stations(int rows, int per_row, bool moving) {
  return test::sample_rows(
      [&](double s, double t) {
        const double b = 5 + 1.5 * std::sin(t * M_PI), d = 3 + 0.6 * t;
        double l0 = 0.6 * b, l1 = 0.8 * d, l2 = 0.4 * b;
        if (moving) l0 *= 0.8 + 0.4 * t;
        const double x = s * (l0 + l1 + l2);
        if (x < l0) return Point(30 * t, x, 0.05 * x * x / l0);
        if (x < l0 + l1) return Point(30 * t, l0 + 0.1 * (x - l0), 0.05 * l0 + (x - l0));
        return Point(30 * t, l0 + 0.1 * l1 - (x - l0 - l1), 0.05 * l0 + l1);
      },
      std::vector<int>(static_cast<std::size_t>(rows), per_row));
}

// A smooth sheet with one narrow bump.
Rows bump_sheet() {
  return test::sample_rows(
      [](double s, double t) {
        const double r2 = (s - 0.6) * (s - 0.6) + (t - 0.4) * (t - 0.4);
        return Point(s, t, 0.1 * std::sin(2 * s) + 0.05 * t * t + 0.05 * std::exp(-r2 / 9e-4));
      },
      std::vector<int>(40, 120));
}

Rows smooth_sheet() {
  return test::sample_rows(
      [](double s, double t) { return Point(s, t, 0.2 * std::sin(3 * s + t) * std::cos(2 * t)); },
      std::vector<int>(30, 80));
}

TEST(AdaptiveKnots, CorneredSectionsAndALocalBumpNeedAtLeastThirtyPercentFewer) {
  const std::pair<const char*, Rows> sets[] = {{"box stations", box_stations(30, 160, false)},
                                               {"moving corners", box_stations(30, 200, true)},
                                               {"bump sheet", bump_sheet()}};
  for (const auto& [name, rows] : sets) {
    SCOPED_TRACE(name);
    const test::UniformAndAdaptive p = test::fit_both(rows, 1e-3);
    test::report(name, 1e-3, p);
    EXPECT_LE(test::count(p.adaptive), 0.7 * test::count(p.uniform));
    EXPECT_TRUE(p.adaptive.surface.non_uniform());
    // The report says which knots made it, and so does its JSON (read back).
    EXPECT_EQ(p.adaptive.report.knots, KnotRule::kAdaptive);
    EXPECT_EQ(p.uniform.report.knots, KnotRule::kUniform);
    EXPECT_EQ(
        io::report_from_json_text(io::report_to_json_text(p.adaptive.report, -1), "r.json").knots,
        KnotRule::kAdaptive);
    test::expect_holds_at_parameters(rows, p.adaptive);
  }
}

TEST(AdaptiveKnots, NeverMoreThanUniform) {
  std::vector<std::pair<std::string, Rows>> sets;
  sets.emplace_back("smooth sheet", smooth_sheet());
  sets.emplace_back("box stations", box_stations(12, 60, false));
  for (const char* e : {"ship_px121_stations", "height_field_small", "table1_synthetic"})
    sets.emplace_back(e, test::load_rows(test::example(std::string(e) + ".rows")));
  for (const auto& [name, rows] : sets)
    for (double f : {1e-2, 1e-3}) {
      SCOPED_TRACE(name);
      const test::UniformAndAdaptive p = test::fit_both(rows, f);
      test::report(name.c_str(), f, p);
      EXPECT_LE(test::count(p.adaptive), test::count(p.uniform));
      if (test::count(p.adaptive) == test::count(p.uniform)) {
        // Not smaller: the uniform surface itself, bit for bit.
        test::expect_uniform_kept(p);
      }
      test::expect_holds_at_parameters(rows, p.adaptive);
    }
}

}  // namespace
}  // namespace sfit
