// Derivatives from one basis pass, grids, curvature and closest points (sfit/surface_eval.h),
// against the general algorithm (NURBS Book A2.3), exact polynomial surfaces and geometry.
#include "sfit/surface_eval.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <random>

#include "basis_upto.h"
#include "knots.h"
#include "sfit/error.h"

namespace sfit {
namespace {

TEST(BasisUpto, EqualsTheGeneralAlgorithmAndEvalBasis) {
  std::array<double, 3 * (kMaxDegree + 1)> fast, general;
  std::array<double, kMaxDegree + 1> values;
  std::mt19937 rng(5);
  for (bool periodic : {false, true})
    for (int p = 1; p <= 9; ++p)
      for (int n : {p + 1, p + 3, 3 * p + 7}) {
        const double end = domain_end(p, n, periodic);
        std::uniform_real_distribution<double> t_of(-0.5, end + 0.5);
        for (int k = 0; k < 200; ++k) {
          const double t = k < 3 ? end * k / 2 : t_of(rng);
          const int f1 = eval_basis_upto(p, n, periodic, t, 2, fast.data());
          const int f2 = eval_basis_derivatives(p, n, periodic, t, 2, general.data());
          const int f3 = eval_basis(p, n, periodic, t, values.data());
          ASSERT_EQ(f1, f2);
          ASSERT_EQ(f1, f3);
          for (int a = 0; a <= p; ++a) {
            EXPECT_EQ(fast[a], values[a]) << "p=" << p << " n=" << n << " t=" << t;
            for (int d = 1; d <= 2; ++d)
              EXPECT_NEAR(fast[d * (p + 1) + a], general[d * (p + 1) + a], 1e-11 * p * p)
                  << "p=" << p << " n=" << n << " t=" << t << " d=" << d;
          }
        }
      }
}

// z = a u^2 + b v^2 over x = u, y = v, exactly: degree 2 with control points from the
// blossoms (x: the Greville abscissae; u^2: t_{i+1} t_{i+2}).
Surface paraboloid(double a, double b, int nu = 7, int nv = 6) {
  Surface s;
  s.degree_u = s.degree_v = 2;
  s.count_u = nu;
  s.count_v = nv;
  const auto ku = clamped_uniform_knots(2, nu), kv = clamped_uniform_knots(2, nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      s.control.emplace_back((ku[i + 1] + ku[i + 2]) / 2, (kv[j + 1] + kv[j + 2]) / 2,
                             a * ku[i + 1] * ku[i + 2] + b * kv[j + 1] * kv[j + 2]);
  return s;
}

Surface wavy(bool pu, bool pv) {
  Surface s;
  s.degree_u = 3;
  s.degree_v = 4;
  s.periodic_u = pu;
  s.periodic_v = pv;
  s.count_u = 9;
  s.count_v = 11;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> r(-1, 1);
  for (int i = 0; i < s.count_u * s.count_v; ++i) s.control.emplace_back(r(rng), r(rng), r(rng));
  return s;
}

TEST(SurfaceDerivatives, EqualSurfaceDerivativesAndEvaluate) {
  for (bool pu : {false, true})
    for (bool pv : {false, true}) {
      const Surface s = wavy(pu, pv);
      for (int k = 0; k <= 40; ++k)
        for (int m = 0; m <= 40; ++m) {
          const double u = -0.3 + (s.u_end() + 0.6) * k / 40, v = s.v_end() * m / 40;
          Point ref[6], fast[6], one[3], zero[1];
          s.derivatives(u, v, ref);
          surface_derivatives(s, u, v, 2, fast);
          surface_derivatives(s, u, v, 1, one);
          surface_derivatives(s, u, v, 0, zero);
          EXPECT_EQ(fast[0], s.evaluate(u, v));
          EXPECT_EQ(zero[0], s.evaluate(u, v));
          for (int d = 0; d < 6; ++d) EXPECT_LE((fast[d] - ref[d]).norm(), 1e-11) << d;
          for (int d = 0; d < 3; ++d) EXPECT_EQ(one[d], fast[d]);
          const int du[6] = {0, 1, 0, 2, 1, 0}, dv[6] = {0, 0, 1, 0, 1, 2};
          for (int d = 0; d < 6; ++d) EXPECT_EQ(surface_partial(s, u, v, du[d], dv[d]), fast[d]);
        }
    }
}

TEST(SurfaceDerivatives, GridEqualsPointwiseBitForBit) {
  const Surface s = wavy(true, false);
  const std::vector<double> u = {-1, 0, 0.3, 2.5, 8.9, 9, 12}, v = {0, 0.01, 3.3, 7, 7.5};
  for (int order = 0; order <= 2; ++order) {
    const DirectionBasis bu = direction_basis(s, true, u, order);
    const DirectionBasis bv = direction_basis(s, false, v, order);
    for (std::size_t i = 0; i < u.size(); ++i)
      for (std::size_t j = 0; j < v.size(); ++j) {
        Point g[6], p[6];
        surface_derivatives(s, bu, i, bv, j, g);
        surface_derivatives(s, u[i], v[j], order, p);
        for (int d = 0; d < derivative_count(order); ++d) EXPECT_EQ(g[d], p[d]);
        if (order == 1) {
          const DirectionBasis b0u = direction_basis(s, true, u, 0);
          const DirectionBasis b0v = direction_basis(s, false, v, 0);
          EXPECT_EQ(surface_partial(s, bu, i, b0v, j, 1, 0), p[1]);
          EXPECT_EQ(surface_partial(s, b0u, i, bv, j, 0, 1), p[2]);
        }
      }
  }
  Point out[6];
  EXPECT_THROW(surface_derivatives(s, 0, 0, 3, out), Error);
}

TEST(SurfaceCurvature, ParaboloidHasTheGraphsCurvature) {
  const double a = 0.3, b = -0.2;
  const Surface s = paraboloid(a, b);
  for (double u : {0.0, 0.7, 2.5, 4.0, 5.0})
    for (double v : {0.0, 1.5, 3.2, 4.0}) {
      Point d[6];
      surface_derivatives(s, u, v, 2, d);
      EXPECT_NEAR(d[0].z(), a * u * u + b * v * v, 1e-12);
      const double fu = 2 * a * u, fv = 2 * b * v, fuu = 2 * a, fvv = 2 * b,
                   w = 1 + fu * fu + fv * fv;
      const double K = fuu * fvv / (w * w);
      const double H = ((1 + fv * fv) * fuu + (1 + fu * fu) * fvv) / (2 * std::pow(w, 1.5));
      const Curvature c = surface_curvature(s, u, v);
      EXPECT_NEAR(c.gaussian, K, 1e-12);
      EXPECT_NEAR(c.mean, H, 1e-12);
      EXPECT_NEAR(c.k1 * c.k2, K, 1e-12);
      EXPECT_NEAR((c.k1 + c.k2) / 2, H, 1e-12);
      EXPECT_GE(c.k1, c.k2);
    }
  // At the origin the principal curvatures are 2a and 2b.
  const Curvature o = surface_curvature(s, 0, 0);
  EXPECT_NEAR(o.k1, 2 * a, 1e-12);
  EXPECT_NEAR(o.k2, 2 * b, 1e-12);
}

TEST(ClosestPoint, OffsetAlongTheNormalComesBack) {
  const Surface s = paraboloid(0.1, 0.05);
  const ClosestPointFinder finder(s);
  for (double u : {0.4, 1.7, 3.3, 4.6})
    for (double v : {0.2, 2.1, 3.9})
      for (double off : {-0.5, 0.0, 0.8}) {
        Point d[3];
        surface_derivatives(s, u, v, 1, d);
        const Point n = d[1].cross(d[2]).normalized();
        const ClosestPoint c = finder.find(d[0] + off * n);
        EXPECT_NEAR(c.u, u, 1e-9);
        EXPECT_NEAR(c.v, v, 1e-9);
        EXPECT_NEAR(c.distance, std::abs(off), 1e-9);
      }
}

TEST(ClosestPoint, EdgesAndCornersOfAPlane) {
  const Surface s = paraboloid(0, 0);  // the plane z = 0 over [0, 5] x [0, 4]
  const ClosestPointFinder finder(s);
  ClosestPoint c = finder.find(Point(-2, 1.5, 3));
  EXPECT_EQ(c.u, 0.0);
  EXPECT_NEAR(c.v, 1.5, 1e-12);
  c = finder.find(Point(2.5, 7, -1));
  EXPECT_NEAR(c.u, 2.5, 1e-12);
  EXPECT_EQ(c.v, 4.0);
  c = finder.find(Point(9, -3, 0.5));
  EXPECT_EQ(c.u, 5.0);
  EXPECT_EQ(c.v, 0.0);
  EXPECT_NEAR(c.distance, std::sqrt(16 + 9 + 0.25), 1e-12);
}

// A smooth bumpy sheet over [0, 8] x [0, 10] (control points on a grid, heights random), or
// closed along u, a bumpy tube of radius about 3 around the y axis.
Surface bumpy(bool pu) {
  Surface s = wavy(pu, false);
  for (int i = 0; i < s.count_u; ++i)
    for (int j = 0; j < s.count_v; ++j) {
      Point& c = s.at(i, j);
      const double a = 2 * 3.141592653589793 * i / s.count_u, r = 3 + 0.6 * c.z();
      c = pu ? Point(r * std::cos(a), j, r * std::sin(a)) : Point(i, j, 0.6 * c.z());
    }
  return s;
}

TEST(ClosestPoint, NeverFartherThanADenseSample) {
  for (bool pu : {false, true}) {
    const Surface s = bumpy(pu);
    const ClosestPointFinder finder(s);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> r(-1.5, 1.5);
    for (int k = 0; k < 30; ++k) {
      const Point p = pu ? Point(2 * r(rng), 5 + 4 * r(rng), 2 * r(rng))
                         : Point(4 + 3 * r(rng), 5 + 4 * r(rng), r(rng));
      const ClosestPoint c = finder.find(p);
      EXPECT_NEAR((s.evaluate(c.u, c.v) - p).norm(), c.distance, 1e-12);
      double dense = 1e300;
      for (int a = 0; a <= 300; ++a)
        for (int b = 0; b <= 300; ++b)
          dense =
              std::min(dense, (s.evaluate(s.u_end() * a / 300, s.v_end() * b / 300) - p).norm());
      // Newton from the nearest sample finds the nearest point, not a farther local minimum.
      EXPECT_LE(c.distance, dense + 1e-12)
          << "point " << k << " periodic " << pu << " at " << c.u << " " << c.v;
    }
  }
}

}  // namespace
}  // namespace sfit
