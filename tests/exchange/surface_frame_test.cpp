// Scale-free mesh geometry (src/exchange/surface_frame.h): the same surface at every accepted
// size (1e-149 ... 1e149) and at a far offset gives the same normals, curvature times the
// size, and the same density; poles get a limit normal and curvature, never NaN.
#include "surface_frame.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "exchange_cases.h"
#include "sfit/exchange/tessellate.h"

namespace sfit::exchange {
namespace {

Surface scaled(Surface s, double size, const Point& offset = Point::Zero()) {
  for (Point& p : s.control) p = p * size + offset;
  return s;
}

// A surface of revolution closed in u whose first column of control points is one point: a
// pole at v = 0 where S_u vanishes (a nose, a blade tip); the second ring at the pole's
// height makes the tip smooth (one tangent plane), so the curvature has a limit there.
Surface capped_dome() {
  Surface s;
  s.degree_u = s.degree_v = 3;
  s.periodic_u = true;
  s.count_u = 8;
  s.count_v = 5;
  const double r[5] = {0, 0.5, 1, 1.2, 1.2}, z[5] = {1.5, 1.5, 1.1, 0.5, 0};  // a flat tip
  s.control.resize(40);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 5; ++j) {
      const double a = 2 * std::numbers::pi * i / 8;
      s.at(i, j) = Point(r[j] * std::cos(a), r[j] * std::sin(a), z[j]);
    }
  return s;
}

TEST(SurfaceFrame, NormalsCurvatureAndDensityDoNotDependOnSizeOrOffset) {
  for (const auto* c : test::must_pass_cases()) {
    SCOPED_TRACE(c->name);
    const Surface& s = c->fit.surface;
    const Mesh ref = tessellate(s, 16, 12);
    const Density dref = choose_density(s, 1e-3 * c->diagonal);
    const Curvature kref = curvature(s, 0.37 * s.u_end(), 0.61 * s.v_end());
    ASSERT_TRUE(std::isfinite(kref.mean) && std::isfinite(kref.gaussian));
    const std::vector<std::pair<double, Point>> cases = {{1e149, Point::Zero()},
                                                         {1e-149, Point::Zero()},
                                                         {1e100, Point::Zero()},
                                                         {1e-100, Point::Zero()},
                                                         {1.0, Point(1e7, -1e7, 1e7)}};
    for (const auto& [size, offset] : cases) {
      SCOPED_TRACE(size);
      const Surface t = scaled(s, size, offset);
      const Mesh m = tessellate(t, 16, 12);
      double worst = 0;
      for (std::size_t k = 0; k < m.normals.size(); ++k) {
        ASSERT_TRUE(m.normals[k].allFinite()) << k;
        worst = std::max(worst, (m.normals[k] - ref.normals[k]).norm());
      }
      // A far offset rounds the control points to 1e7 * 2^-52 = 2e-9 of a unit-size surface.
      EXPECT_LE(worst, offset.norm() > 0 ? 1e-6 : 1e-12);
      const Density d = choose_density(t, 1e-3 * c->diagonal * size);
      EXPECT_EQ(d.samples_u, dref.samples_u);
      EXPECT_EQ(d.samples_v, dref.samples_v);
      EXPECT_NEAR(d.bound / size, dref.bound, (offset.norm() > 0 ? 1e-6 : 1e-9) * dref.bound);
      const Curvature k = curvature(t, 0.37 * s.u_end(), 0.61 * s.v_end());
      const double tol = offset.norm() > 0 ? 1e-5 : 1e-10;
      EXPECT_NEAR(k.mean * size, kref.mean, tol * std::abs(kref.mean) + 1e-300);
      EXPECT_NEAR(k.gaussian * size * size, kref.gaussian, tol * std::abs(kref.gaussian) + 1e-300);
      EXPECT_FALSE(k.limit);
    }
  }
}

TEST(SurfaceFrame, APoleHasOneLimitNormalAndAFiniteCurvature) {
  const Surface s = capped_dome();
  for (double size : {1.0, 1e-140, 1e140}) {
    SCOPED_TRACE(size);
    const Surface t = scaled(s, size);
    const Mesh m = tessellate(t, 16, 9);
    // Row b = 0 is the pole: one normal for all its samples, along the axis (+z or -z).
    for (int a = 0; a < m.samples_u; ++a) {
      const Point& n = m.normals[m.index(a, 0)];
      EXPECT_NEAR(std::abs(n.z()), 1.0, 1e-6) << a;
      EXPECT_EQ(n, m.normals[m.index(0, 0)]);
    }
    // The pole's normal continues the normals around it.
    EXPECT_GT(m.normals[m.index(0, 0)].dot(m.normals[m.index(0, 1)]), 0.5);
    const Curvature k = curvature(t, 0.3, 0.0);
    EXPECT_TRUE(k.limit);
    EXPECT_TRUE(std::isfinite(k.mean) && std::isfinite(k.gaussian));
    // Beside the pole: the limit is the curvature just next to it.
    const Curvature near = curvature(t, 0.3, 1e-3);
    EXPECT_NEAR(k.gaussian, near.gaussian, 0.05 * std::abs(near.gaussian));
    EXPECT_GT(k.gaussian * size * size, 0);  // a dome: elliptic at its tip
  }
}

TEST(SurfaceFrame, OnlyAGenuinelyDegeneratePointIsNaN) {
  Surface s = capped_dome();
  for (Point& p : s.control) p = Point(1, 2, 3);  // a whole surface collapsed to a point
  const Curvature k = curvature(s, 0.5, 0.5);
  EXPECT_TRUE(std::isnan(k.mean));
  EXPECT_TRUE(std::isnan(k.gaussian));
  const Mesh m = tessellate(s, 5, 4);  // still a mesh with unit normals
  for (const Point& n : m.normals) EXPECT_NEAR(n.norm(), 1.0, 1e-12);
}

}  // namespace
}  // namespace sfit::exchange
