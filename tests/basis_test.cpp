#include "basis.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "knots.h"
#include "reference_eval.h"
#include "sfit/curve.h"

namespace sfit {
namespace {

TEST(Basis, PartitionOfUnityAndNonNegativity) {
  std::array<double, kMaxDegree + 1> b;
  for (bool periodic : {false, true})
    for (int p = 1; p <= kMaxDegree; ++p)
      for (int n : {p + 1, p + 2, 2 * p + 5}) {
        const double end = domain_end(p, n, periodic);
        for (int s = 0; s <= 97; ++s) {
          const double t = end * s / 97.0;
          eval_basis(p, n, periodic, t, b.data());
          double sum = 0;
          for (int i = 0; i <= p; ++i) {
            EXPECT_GE(b[i], -1e-14) << "p=" << p << " n=" << n << " t=" << t;
            sum += b[i];
          }
          EXPECT_NEAR(sum, 1.0, 1e-12) << "p=" << p << " n=" << n << " t=" << t;
        }
      }
}

TEST(Basis, ClampedEndsInterpolateEndControlPoints) {
  std::array<double, kMaxDegree + 1> b;
  for (int p = 1; p <= kMaxDegree; ++p) {
    const int n = p + 4;
    int first = eval_basis(p, n, false, 0.0, b.data());
    EXPECT_EQ(first, 0);
    EXPECT_DOUBLE_EQ(b[0], 1.0);
    first = eval_basis(p, n, false, domain_end(p, n, false), b.data());
    EXPECT_EQ(first + p, n - 1);
    EXPECT_DOUBLE_EQ(b[p], 1.0);
  }
}

TEST(Basis, MatchesTextbookCoxDeBoorOnFullKnots) {
  std::array<double, kMaxDegree + 1> b;
  for (bool periodic : {false, true})
    for (int p : {1, 2, 3, 5, 8}) {
      const int n = p + 6;
      const auto knots = periodic ? periodic_uniform_knots(p, n) : clamped_uniform_knots(p, n);
      const int full = periodic ? n + p : n;
      const double end = domain_end(p, n, periodic);
      for (double t : {0.0, 0.3, 1.0, 2.71, end - 0.2, end * 0.999}) {
        const int first = eval_basis(p, n, periodic, t, b.data());
        for (int i = 0; i < full; ++i) {
          double mine = 0;
          for (int a = 0; a <= p; ++a)
            if ((first + a) == i) mine = b[a];
          EXPECT_NEAR(mine, test::cox_de_boor(knots, i, p, t, knots[full]), 1e-13)
              << "periodic=" << periodic << " p=" << p << " i=" << i << " t=" << t;
        }
      }
    }
}

TEST(Basis, PeriodicCurveWrapsSmoothlyAtTheSeam) {
  Curve c;
  c.periodic = true;
  for (int p : {2, 3, 4}) {
    c.degree = p;
    c.control.clear();
    for (int i = 0; i < 9; ++i)
      c.control.push_back(Point(std::cos(i * 0.7), std::sin(i * 1.3), 0.1 * i * i));
    const double n = c.domain_end();
    for (int d = 0; d < p; ++d) {
      const Point a = c.derivative(n - 1e-9, d), b = c.derivative(1e-9, d);
      EXPECT_NEAR((a - b).norm(), 0.0, 1e-6 * (1 + a.norm()))
          << "degree " << p << " derivative " << d;
    }
    EXPECT_NEAR((c.evaluate(n + 0.25) - c.evaluate(0.25)).norm(), 0.0, 1e-12);
  }
}

TEST(Basis, DerivativesMatchFiniteDifferences) {
  Curve c;
  c.degree = 4;
  for (int i = 0; i < 10; ++i) c.control.push_back(Point(i, std::sin(i), std::cos(2 * i)));
  const double h = 1e-5;
  for (double t : {0.5, 1.7, 3.2, 5.5}) {
    const Point fd1 = (c.evaluate(t + h) - c.evaluate(t - h)) / (2 * h);
    const Point fd2 = (c.evaluate(t + h) - 2 * c.evaluate(t) + c.evaluate(t - h)) / (h * h);
    EXPECT_NEAR((c.derivative(t, 1) - fd1).norm(), 0, 1e-7);
    EXPECT_NEAR((c.derivative(t, 2) - fd2).norm(), 0, 1e-3);
  }
}

}  // namespace
}  // namespace sfit
