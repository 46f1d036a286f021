// Arc-length re-representation (docs/seams.md): each row curve sampled at equal arc length
// instead of the paper's parameters, so that a row's concentration of points does not
// distort the surface; the guarantee still holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "parameters.h"
#include "rerepresent.h"
#include "sfit/curve_fit.h"
#include "sfit/parametrization.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

// Consecutive distances between the re-represented curve at its Greville abscissae (where
// the samples were placed; interpolated, as no repair was needed): largest over smallest.
double spread(const Rerepresentation& r, int count) {
  const ReparameterMap map(3, count, 3, count, false);
  const auto& g = map.targets();
  double lo = INFINITY, hi = 0;
  for (std::size_t l = 0; l + 1 < g.size(); ++l) {
    const double d = (r.curve.evaluate(g[l + 1]) - r.curve.evaluate(g[l])).norm();
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  return hi / lo;
}

TEST(ArcLength, SamplesAtEqualArcLengthAndHolds) {
  // A row with its points crowded at one end: the paper's samples (by index) crowd there too.
  std::vector<Point> p;
  for (int k = 0; k < 60; ++k) {
    const double s = std::pow(k / 59.0, 3);
    p.push_back(Point(4 * s, std::sin(4 * s), 0));
  }
  CurveFitOptions o;
  o.bound = Point::Constant(2e-2);
  const CurveFit fit = fit_curve(p, o);
  // The fit raises the count until the re-representation holds (the caller's half of the
  // guarantee): so here.
  int count = fit.curve.count() + 1;  // (at its own count a curve is kept as it is)
  Rerepresentation arc;
  for (; count < 60; ++count) {
    arc = rerepresent(fit, p, 3, count, false, o.bound, {}, Resampling::kArcLength);
    if (arc.holds) break;
  }
  ASSERT_TRUE(arc.holds);
  EXPECT_EQ(arc.repair_rounds, 0);
  const Rerepresentation paper = rerepresent(fit, p, 3, count, false, o.bound);
  // The samples keep the paper's pattern (the Greville sequence, 1/3 steps at the ends of a
  // cubic) in arc length instead of parameter: the spread is that of the Greville steps.
  EXPECT_LT(spread(arc, count), 3.2);
  EXPECT_GT(spread(paper, count), 3 * spread(arc, count));
  Resampling r;
  ASSERT_TRUE(parse_resampling("arc_length", r));
  EXPECT_EQ(to_string(r), "arc_length");
  EXPECT_FALSE(parse_resampling("arc", r));
}

TEST(ArcLength, SurfaceFitHoldsTheTolerance) {
  for (const char* name : {"table1_synthetic.rows", "ship_px121_stations.rows"}) {
    const Rows rows = test::load_rows(test::example(name));
    FitOptions o;
    o.tolerance = relative_tolerance(rows, 1e-3);
    o.rerepresentation = Resampling::kArcLength;
    const FitResult f = fit_surface(rows, o);
    EXPECT_TRUE(f.report.within_tolerance) << name;
    EXPECT_LE(test::reference_deviation(f, rows).maxCoeff(), o.tolerance.x() * (1 + 1e-9)) << name;
  }
}

}  // namespace
}  // namespace sfit
