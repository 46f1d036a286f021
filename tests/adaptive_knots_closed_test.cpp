// --knots adaptive along closed rows (a periodic u direction). Closed sections with sharp
// corners (rectangles whose size changes along the set, a blunt-trailing-edge airfoil) need at
// least 30% fewer control points on adapted periodic knots than on uniform ones; every point
// holds T (an independent evaluation of the written surface), nothing folds, and the periodic
// non-uniform knots survive the JSON round trip. Smooth closed sections keep the uniform surface.
#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_pair.h"
#include "reference_eval.h"
#include "sfit/fold_check.h"
#include "sfit/io/surface_json.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

// A rectangle of sides 2a x 2b walked once around at arc length s (0 ... 1), starting at a
// side's middle: four sharp corners at the same s in every section.
Point rectangle(double s, double a, double b) {
  const double per = 4 * (a + b);
  double x = s * per;
  const double sides[4] = {b, 2 * a, 2 * b, 2 * a};
  const Point corners[4] = {{a, b, 0}, {-a, b, 0}, {-a, -b, 0}, {a, -b, 0}};
  const Point dirs[4] = {{0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {1, 0, 0}};
  Point start(a, 0, 0);
  for (int k = 0; k < 4; ++k) {
    if (x <= sides[k]) return start + x * dirs[k];
    x -= sides[k];
    start = corners[k];
  }
  return start + std::min(x, b) * Point(0, 1, 0);
}

Rows rectangle_sections() {
  return test::sample_rows(
      [](double s, double t) {
        const double scale = 1 + 0.4 * std::sin(M_PI * t);
        Point p = rectangle(s, 2 * scale, scale);
        p.z() = 10 * t;
        return p;
      },
      std::vector<int>(14, 240), true);
}

// An airfoil-like section with a blunt trailing edge: a thickness t(x) closed by a flat base
// at x = 1 (two corners), walked at arc length from the middle of the base.
Rows blunt_airfoils() {
  return test::sample_rows(
      [](double s, double t) {
        const double c = 5 - 2 * t, th = 0.12 + 0.06 * t, base = 0.06;
        // Upper surface s in [0.02, 0.5): x from 1 to 0; lower [0.5, 0.98): 0 to 1; the base
        // takes the rest.
        auto half = [&](double x) {
          return base / 2 + th * (1.4 * std::sqrt(x) - 1.2 * x - 0.2 * x * x) * (1 - x);
        };
        Point p;
        if (s < 0.02 || s >= 0.98) {
          const double w = s < 0.02 ? s / 0.02 : (s - 1) / 0.02;  // -1 ... 1 across the base
          p = Point(1, 0.5 * base * w, 0);
        } else if (s < 0.5) {
          const double x = 0.5 * (1 + std::cos(M_PI * (s - 0.02) / 0.48));
          p = Point(x, half(x), 0);
        } else {
          const double x = 0.5 * (1 - std::cos(M_PI * (s - 0.5) / 0.48));
          p = Point(x, -half(x), 0);
        }
        return Point(c * p.x(), c * p.y(), 8 * t);
      },
      std::vector<int>(16, 200), true);
}

Rows ellipses() {
  return test::sample_rows(
      [](double s, double t) {
        const double a = 2 + 0.5 * t, b = 1 + 0.3 * std::sin(M_PI * t);
        return Point(a * std::cos(2 * M_PI * s), b * std::sin(2 * M_PI * s), 5 * t);
      },
      std::vector<int>(12, 150), true);
}

TEST(AdaptiveKnotsClosed, CorneredClosedSectionsNeedAtLeastThirtyPercentFewer) {
  const std::pair<const char*, Rows> sets[] = {{"rectangles", rectangle_sections()},
                                               {"blunt airfoils", blunt_airfoils()}};
  for (const auto& [name, rows] : sets) {
    SCOPED_TRACE(name);
    const test::UniformAndAdaptive p = test::fit_both(rows, 1e-3, true);
    test::report(name, 1e-3, p);
    ASSERT_TRUE(p.uniform.surface.periodic_u);
    EXPECT_LE(test::count(p.adaptive), 0.7 * test::count(p.uniform));
    EXPECT_EQ(p.adaptive.report.knots, KnotRule::kAdaptive);
    const Surface& s = p.adaptive.surface;
    EXPECT_TRUE(s.periodic_u);
    EXPECT_FALSE(s.knots_u.uniform());
    EXPECT_TRUE(s.knots_u.periodic());
    test::expect_holds_at_parameters(rows, p.adaptive);
    // The periodic non-uniform knots read back as written: same knots, same points, same
    // values.
    const Surface back = io::surface_from_json_text(io::surface_to_json_text(s), "s.json");
    EXPECT_TRUE(back.periodic_u);
    EXPECT_EQ(back.knots_u, s.knots_u);
    EXPECT_EQ(back.knots_v, s.knots_v);
    EXPECT_EQ(back.control, s.control);
    for (double u : {0.0, 0.3 * s.u_end(), 0.999 * s.u_end()})
      EXPECT_EQ(back.evaluate(u, 0.5 * s.v_end()), s.evaluate(u, 0.5 * s.v_end()));
  }
}

TEST(AdaptiveKnotsClosed, SmoothClosedSectionsKeepTheUniformSurface) {
  const Rows rows = ellipses();
  for (double f : {1e-2, 1e-3}) {
    const test::UniformAndAdaptive p = test::fit_both(rows, f, true);
    test::report("ellipses", f, p);
    EXPECT_EQ(test::count(p.adaptive), test::count(p.uniform));
    test::expect_uniform_kept(p);
    test::expect_holds_at_parameters(rows, p.adaptive);
  }
}

}  // namespace
}  // namespace sfit
