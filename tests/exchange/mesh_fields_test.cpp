// The VTK point data (src/exchange/mesh_fields.h): the deviation interpolated on the grid
// reproduces any field linear in (u, v) exactly, and stays within the data's; curvature
// clipping at the 1st and 99th percentiles.
#include "mesh_fields.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "exchange_cases.h"

namespace sfit::exchange::detail {
namespace {

TEST(MeshFields, GridDeviationInterpolatesTheDataLinearly) {
  for (const auto* c : test::must_pass_cases()) {
    SCOPED_TRACE(c->name);
    const Surface& s = c->fit.surface;
    DataPoints d = data_points(s, &c->fit, &c->rows);
    ASSERT_EQ(d.points.size(), c->rows.total_points());
    // The real deviation: S(u, v) - D at the data, within T.
    for (std::size_t i = 0; i < d.points.size(); ++i)
      EXPECT_LE(deviation_ratio(d.deviation[i], d.tolerance), 1.0 + 1e-12);
    const Mesh m = tessellate(s, 23, 17);
    const std::vector<Point> real = grid_deviation(s, m, d, c->rows);
    double worst = 0;
    for (const Point& g : real) worst = std::max(worst, deviation_ratio(g, d.tolerance));
    EXPECT_LE(worst, 1.0 + 1e-12);  // a blend of the data's deviations
    // A field linear in v (and, in an open direction, in u) comes back exactly wherever the
    // sample lies within the data's parameters.
    double vlo = 1e300, vhi = -1e300;
    for (double v : d.v) vlo = std::min(vlo, v), vhi = std::max(vhi, v);
    if (!c->fit.v_points.empty()) {
      // Points with their own v (parameters geometric): within the v the outer rows reach at
      // every u (the lowest row's largest v, the highest row's smallest).
      std::size_t lo = 0, hi = 0;
      std::vector<double> mean(c->rows.size(), 0.0), least(c->rows.size(), 1e300),
          most(c->rows.size(), -1e300);
      for (std::size_t j = 0, k = 0; j < c->rows.size(); ++j) {
        for (std::size_t i = 0; i < c->rows[j].size(); ++i, ++k) {
          mean[j] += d.v[k] / static_cast<double>(c->rows[j].size());
          least[j] = std::min(least[j], d.v[k]);
          most[j] = std::max(most[j], d.v[k]);
        }
        if (mean[j] < mean[lo]) lo = j;
        if (mean[j] > mean[hi]) hi = j;
      }
      vlo = most[lo];
      vhi = least[hi];
    }
    // And in u where every row has points either side (rows reach different u there).
    double ulo = -1e300, uhi = 1e300;
    if (!c->fit.v_points.empty())
      for (std::size_t j = 0, k = 0; j < c->rows.size(); k += c->rows[j].size(), ++j) {
        const auto [a, b] =
            std::minmax_element(d.u.begin() + static_cast<std::ptrdiff_t>(k),
                                d.u.begin() + static_cast<std::ptrdiff_t>(k + c->rows[j].size()));
        ulo = std::max(ulo, *a);
        uhi = std::min(uhi, *b);
      }
    const bool linear_u = !m.periodic_u;  // the mesh wraps where the surface closes
    for (std::size_t i = 0; i < d.points.size(); ++i)
      d.deviation[i] = Point(linear_u ? d.u[i] : 0.0, 2 * d.v[i], 1);
    const std::vector<Point> lin = grid_deviation(s, m, d, c->rows);
    for (int b = 0; b < m.samples_v; ++b) {
      if (!s.periodic_v && (m.v[b] < vlo || m.v[b] > vhi)) continue;
      for (int a = 0; a < m.samples_u; ++a) {
        if (m.u[a] < ulo || m.u[a] > uhi) continue;
        const Point& g = lin[m.index(a, b)];
        EXPECT_NEAR(g.z(), 1.0, 1e-12);
        if (!s.periodic_v) {
          EXPECT_NEAR(g.y(), 2 * m.v[b], 1e-9);
        }
        if (linear_u) {
          EXPECT_NEAR(g.x(), m.u[a], 1e-9) << a << ", " << b;
        }
      }
    }
  }
}

TEST(MeshFields, CurvatureIsClippedToItsRobustRange) {
  const auto* c = test::must_pass_cases()[2];  // the blade: a sharp trailing edge
  const SurfaceFrame f(c->fit.surface);
  const Mesh m = tessellate(c->fit.surface, 60, 40);
  const CurvatureFields k = curvature_fields(f, m, {0.5}, {0.5});
  ASSERT_EQ(k.mean.values.size(), m.vertices.size() + 1);
  std::size_t below = 0, above = 0;
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    ASSERT_TRUE(std::isfinite(k.mean.values[i]));
    EXPECT_GE(k.mean.clipped[i], k.mean.lo);
    EXPECT_LE(k.mean.clipped[i], k.mean.hi);
    if (k.mean.values[i] < k.mean.lo) ++below;
    if (k.mean.values[i] > k.mean.hi) ++above;
    if (k.mean.values[i] >= k.mean.lo && k.mean.values[i] <= k.mean.hi) {
      EXPECT_EQ(k.mean.clipped[i], k.mean.values[i]);
    }
  }
  // About 1 % of the grid on each side.
  EXPECT_LE(below, m.vertices.size() / 50);
  EXPECT_LE(above, m.vertices.size() / 50);
  EXPECT_LT(k.mean.lo, k.mean.hi);
}

}  // namespace
}  // namespace sfit::exchange::detail
