#include "parameters.h"

#include <gtest/gtest.h>

#include <cmath>

#include "knots.h"

namespace sfit {
namespace {

TEST(Parametrization, OpenEndsOnDomainAndGrevilleWhenInterpolating) {
  for (int p = 1; p <= 6; ++p)
    for (int n = p + 1; n <= 25; n += 3)
      for (int N : {n, n + 1, 2 * n + 3}) {
        const auto t = paper_parameters(p, n, false, N);
        ASSERT_EQ(t.size(), static_cast<std::size_t>(N));
        EXPECT_EQ(t.front(), 0.0);
        EXPECT_EQ(t.back(), domain_end(p, n, false));
        for (int j = 1; j < N; ++j) EXPECT_GT(t[j], t[j - 1]);
        if (N == n) {
          for (int j = 0; j < N; ++j) EXPECT_NEAR(t[j], greville(p, n, false, j), 1e-12);
        }
      }
}

TEST(Parametrization, EveryKnotSpanGetsAParameter) {
  // docs/method.md 3: every non-empty knot span holds at least one t (Schoenberg-Whitney).
  for (int p = 1; p <= 5; ++p)
    for (int n = p + 1; n <= 30; ++n)
      for (int N = n; N <= n + 7; ++N) {
        const auto t = paper_parameters(p, n, false, N);
        for (int span = 0; span < n - p; ++span) {
          bool hit = false;
          for (double x : t) hit = hit || (x >= span && x <= span + 1);
          EXPECT_TRUE(hit) << "p=" << p << " n=" << n << " N=" << N << " span " << span;
        }
      }
}

TEST(Parametrization, PaperFormulaOnASmallCase) {
  // N = 5 points, order 4 (degree 3), N_u = 4: A = 3/4; Greville 0, 1/3, 2/3, 1.
  // t_j = Greville at fractional index A*j: 0, 0.25, 0.5, 0.75, 1.
  const auto t = paper_parameters(3, 4, false, 5);
  const double expect[] = {0, 0.25, 0.5, 0.75, 1};
  for (int j = 0; j < 5; ++j) EXPECT_NEAR(t[j], expect[j], 1e-15);
}

TEST(Parametrization, PeriodicIsUniformAndHitsGreville) {
  for (int p : {1, 2, 3, 4}) {
    const auto t = paper_parameters(p, 8, true, 8);
    for (int j = 0; j < 8; ++j) {
      bool found = false;
      for (int i = 0; i < 8; ++i) found = found || std::abs(t[j] - greville(p, 8, true, i)) < 1e-12;
      EXPECT_TRUE(found) << "degree " << p;
    }
    const auto u = paper_parameters(p, 8, true, 20);
    // Uniform steps around the loop (parameters are reduced into [0, 8)).
    for (int j = 1; j < 20; ++j) EXPECT_NEAR(std::fmod(u[j] - u[j - 1] + 8, 8.0), 8.0 / 20, 1e-12);
  }
}

TEST(Parametrization, ReparameterMapSendsSamplesToNewGreville) {
  for (bool periodic : {false, true}) {
    const ReparameterMap m(3, 7, 3, 12, periodic);
    ASSERT_EQ(m.samples().size(), 12u);
    for (std::size_t l = 0; l < 12; ++l) EXPECT_NEAR(m(m.samples()[l]), m.targets()[l], 1e-12);
    if (!periodic) {
      EXPECT_EQ(m(0.0), 0.0);
      EXPECT_EQ(m(domain_end(3, 7, false)), domain_end(3, 12, false));
    }
  }
  // Same count and degree: the identity.
  const ReparameterMap id(3, 9, 3, 9, false);
  for (double t : {0.0, 0.4, 2.2, 5.9, 6.0}) EXPECT_NEAR(id(t), t, 1e-12);
}

TEST(Parametrization, NamesRoundTrip) {
  for (Parametrization p :
       {Parametrization::kPaper, Parametrization::kUniform, Parametrization::kChord,
        Parametrization::kCentripetal, Parametrization::kFewest}) {
    Parametrization q = Parametrization::kPaper;
    ASSERT_TRUE(parse_parametrization(to_string(p), q));
    EXPECT_EQ(q, p);
  }
  Parametrization q = Parametrization::kChord;
  EXPECT_FALSE(parse_parametrization("arc", q));
  EXPECT_EQ(q, Parametrization::kChord);
}

TEST(Parametrization, ChordAndCentripetalPositions) {
  // Steps of 1, 4 and 9 along x (chord 14 in all), then back to the start when closed (14).
  const std::vector<Point> pts = {Point(0, 0, 0), Point(1, 0, 0), Point(5, 0, 0), Point(14, 0, 0)};
  auto near = [](const std::vector<double>& a, const std::vector<double>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-15) << i;
  };
  near(normalized_positions(pts, Parametrization::kChord, false), {0, 1 / 14.0, 5 / 14.0, 1});
  near(normalized_positions(pts, Parametrization::kCentripetal, false), {0, 1 / 6.0, 3 / 6.0, 1});
  near(normalized_positions(pts, Parametrization::kUniform, false), {0, 1 / 3.0, 2 / 3.0, 1});
  near(normalized_positions(pts, Parametrization::kChord, true),
       {0, 1 / 28.0, 5 / 28.0, 14 / 28.0});
  near(normalized_positions(pts, Parametrization::kUniform, true), {0, 0.25, 0.5, 0.75});
  // All points coinciding: uniform, not a division by zero.
  const std::vector<Point> same(5, Point(1, 2, 3));
  near(normalized_positions(same, Parametrization::kChord, false), {0, 0.25, 0.5, 0.75, 1});
}

TEST(Parametrization, ScaledParametersSpanTheDomain) {
  const std::vector<double> f = {0, 0.1, 0.45, 0.8, 1};
  for (int p = 1; p <= 5; ++p)
    for (int n = p + 1; n <= 12; ++n) {
      const auto t = scaled_parameters(p, n, false, f);
      EXPECT_EQ(t.front(), 0.0);
      EXPECT_EQ(t.back(), domain_end(p, n, false));
      EXPECT_NEAR(t[2], 0.45 * (n - p), 1e-12);
    }
  // Uniform positions of a closed row are the paper's periodic rule (to rounding).
  for (int p = 1; p <= 6; ++p)
    for (int count : {7, 8})
      for (int N : {8, 13, 30}) {
        std::vector<double> u(static_cast<std::size_t>(N));
        for (int j = 0; j < N; ++j) u[j] = static_cast<double>(j) / N;
        const auto a = scaled_parameters(p, count, true, u);
        const auto b = paper_parameters(p, count, true, N);
        for (int j = 0; j < N; ++j) EXPECT_NEAR(a[j], b[j], 1e-13) << p << " " << count << " " << N;
      }
}

TEST(Parametrization, ScaledMapKeepsThePosition) {
  // Open: a point at fraction f of the old domain lands at fraction f of the new one, and the
  // samples are the new Greville abscissae's preimages.
  const ReparameterMap m(3, 7, 3, 12, false, true);
  for (double f : {0.0, 0.13, 0.5, 0.91, 1.0}) EXPECT_NEAR(m(f * 4), f * 9, 1e-12) << f;
  for (std::size_t l = 0; l < m.samples().size(); ++l) {
    EXPECT_NEAR(m(m.samples()[l]), m.targets()[l], 1e-12) << l;
    EXPECT_NEAR(m.targets()[l], greville(3, 12, false, static_cast<int>(l)), 1e-15);
  }
  // A degree-2 interpolant of a 3-point row (domain [0, 1]) onto a cubic of 9.
  const ReparameterMap short_row(2, 3, 3, 9, false, true);
  EXPECT_NEAR(short_row(0.5), 3.0, 1e-12);
  // Periodic: the same linear map as the paper's.
  const ReparameterMap a(3, 7, 3, 12, true, true), b(3, 7, 3, 12, true, false);
  for (double t : {0.0, 1.7, 6.2}) EXPECT_EQ(a(t), b(t));
}

}  // namespace
}  // namespace sfit
