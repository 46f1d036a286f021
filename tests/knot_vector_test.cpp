// Non-uniform knots: the KnotVector's rules, evaluation against an independent de Boor, and the
// round trip through the JSON contract.
#include "sfit/knot_vector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "knots.h"
#include "reference_eval.h"
#include "sfit/error.h"
#include "sfit/io/surface_json.h"
#include "sfit/surface_eval.h"
#include "surface_json_value.h"

namespace sfit {
namespace {

ErrorCode code_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.code();
  }
  return ErrorCode::kInternal;  // nothing thrown
}

TEST(KnotVector, DefaultIsUniformAndUniformVectorsStayUniform) {
  EXPECT_TRUE(KnotVector().uniform());
  for (int p = 1; p <= 4; ++p)
    for (int n = p + 1; n < 12; ++n) {
      EXPECT_TRUE(KnotVector::from_full(p, false, clamped_uniform_knots(p, n)).uniform());
      EXPECT_TRUE(KnotVector::from_full(p, true, periodic_uniform_knots(p, n)).uniform());
    }
  // Equal steps of another size are a different parametrisation: kept as given.
  std::vector<double> half = clamped_uniform_knots(3, 8);
  for (double& k : half) k *= 0.5;
  const KnotVector h = KnotVector::from_full(3, false, half);
  EXPECT_FALSE(h.uniform());
  EXPECT_EQ(h.end(), 2.5);
  EXPECT_EQ(h.count(), 8);
}

TEST(KnotVector, RefusesVectorsThatBreakTheContract) {
  auto bad = [](int p, bool periodic, std::vector<double> k) {
    return code_of([&] { KnotVector::from_full(p, periodic, k); });
  };
  EXPECT_EQ(bad(3, false, {0, 0, 0, 0, 2, 1, 3, 3, 3, 3}), ErrorCode::kInputData);  // decreases
  EXPECT_EQ(bad(2, false, {0, 0, 0, 1, 1, 1, 2, 2, 2}), ErrorCode::kInputData);     // mult 3 > 2
  EXPECT_EQ(bad(3, false, {0, 0, 0, 1, 2, 3, 3, 3, 3}), ErrorCode::kInputData);     // open ends
  EXPECT_EQ(bad(3, false, {0, 0, 0, 1, 1, 1}), ErrorCode::kInputData);              // too few
  EXPECT_EQ(bad(3, false, {0, 0, 0, 0, NAN, 2, 2, 2, 2}), ErrorCode::kInputData);
  // Periodic: the spacing must repeat with the period.
  EXPECT_EQ(bad(2, true, {-2, -1, 0, 1, 2.5, 3, 4, 5}), ErrorCode::kInputData);
  EXPECT_EQ(code_of([] {
              const double b[] = {0, 1, 1.5, 4};
              const int m[] = {1, 3};  // 3 > degree 2
              KnotVector::from_breaks(2, false, b, m);
            }),
            ErrorCode::kInputData);
  // A shifted domain is the same surface: it begins at 0 after reading.
  const KnotVector s = KnotVector::from_full(2, false, {5, 5, 5, 6, 6.5, 8, 8, 8});
  EXPECT_EQ(s.full(), (std::vector<double>{0, 0, 0, 1, 1.5, 3, 3, 3}));
}

TEST(KnotVector, BreaksAndMultiplicities) {
  const double b[] = {0, 0.3, 1.0, 2.5};
  const int m[] = {3, 1};
  const KnotVector k = KnotVector::from_breaks(3, false, b, m);
  EXPECT_EQ(k.count(), 3 + 1 + 4);
  EXPECT_EQ(k.full(), (std::vector<double>{0, 0, 0, 0, 0.3, 0.3, 0.3, 1, 2.5, 2.5, 2.5, 2.5}));
  std::vector<double> v;
  std::vector<int> mu;
  k.breaks(v, mu);
  EXPECT_EQ(v, (std::vector<double>{0, 0.3, 1, 2.5}));
  EXPECT_EQ(mu, (std::vector<int>{4, 3, 1, 4}));
  const double pb[] = {0, 0.5, 2, 3};
  const int pm[] = {1, 2, 1};
  const KnotVector p = KnotVector::from_breaks(2, true, pb, pm);
  EXPECT_EQ(p.count(), 4);
  EXPECT_EQ(p.end(), 3);
  EXPECT_EQ(p.full(), (std::vector<double>{-2.5, -1, 0, 0.5, 0.5, 2, 3, 3.5, 3.5}));
  p.breaks(v, mu);
  EXPECT_EQ(v, (std::vector<double>{0, 0.5, 2, 3}));
  EXPECT_EQ(mu, (std::vector<int>{1, 2, 1, 1}));
}

// A surface on random non-uniform knots (interior multiplicities up to the degree).
Surface random_surface(int pu, int pv, bool per_u, bool per_v, std::mt19937& rng) {
  std::uniform_real_distribution<double> r(0, 1);
  auto knots = [&](int p, bool periodic) {
    std::vector<double> b{0};
    std::vector<int> m;
    const int spans = 5 + static_cast<int>(r(rng) * 5);
    if (periodic) m.push_back(1 + static_cast<int>(r(rng) * p));
    for (int i = 1; i <= spans; ++i) {
      b.push_back(b.back() + 0.05 + 2 * r(rng) * r(rng));
      if (i < spans) m.push_back(1 + static_cast<int>(r(rng) * p));
    }
    return KnotVector::from_breaks(p, periodic, b, m);
  };
  Surface s;
  s.degree_u = pu;
  s.degree_v = pv;
  s.periodic_u = per_u;
  s.periodic_v = per_v;
  const KnotVector ku = knots(pu, per_u), kv = knots(pv, per_v);
  s.count_u = ku.count();
  s.count_v = kv.count();
  s.set_knots_u(ku);
  s.set_knots_v(kv);
  for (int i = 0; i < s.count_u * s.count_v; ++i)
    s.control.emplace_back(r(rng) * 4 - 2, r(rng) * 4 - 2, r(rng) * 4 - 2);
  return s;
}

TEST(KnotVector, EvaluationEqualsAnIndependentDeBoor) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> r(0, 1);
  for (int trial = 0; trial < 24; ++trial) {
    const int pu = 1 + trial % 4, pv = 1 + (trial / 4) % 3;
    const Surface s = random_surface(pu, pv, trial % 3 == 1, trial % 5 == 2, rng);
    ASSERT_TRUE(s.non_uniform());
    const std::string text = io::surface_to_json_text(s);
    const test::ReferenceSurface ref = test::reference_from_json_text(text);
    double worst = 0, worst_d = 0;
    for (int k = 0; k < 300; ++k) {
      // Random points, and every breakpoint exactly (the spans' ends; a periodic direction's
      // end is its start, which the reference, closing the last span, would count twice).
      double u = r(rng) * s.u_end(), v = r(rng) * s.v_end();
      if (k < static_cast<int>(s.full_knots_u().size()))
        u = std::clamp(s.full_knots_u()[k], 0.0, s.periodic_u ? 0.0 : s.u_end());
      const auto e = ref.evaluate(u, v);
      const Point p = s.evaluate(u, v);
      worst = std::max(worst, (p - Point(e[0], e[1], e[2])).norm());
      Point d[6];
      surface_derivatives(s, u, v, 2, d);
      EXPECT_EQ(d[0], p) << u << " " << v;  // one basis, the same bits
      Point dd[6];
      s.derivatives(u, v, dd);
      for (int a = 0; a < 6; ++a) worst_d = std::max(worst_d, (dd[a] - d[a]).norm());
      // S_u by central differences of the reference, inside a span.
      const double h = 1e-6;
      if (u > h && u + h < s.u_end()) {
        const auto a = ref.evaluate(u + h, v), b = ref.evaluate(u - h, v);
        const Point fd((a[0] - b[0]) / (2 * h), (a[1] - b[1]) / (2 * h), (a[2] - b[2]) / (2 * h));
        bool at_break = false;  // a C^0 knot has two one-sided derivatives
        for (double t : s.full_knots_u()) at_break |= std::abs(t - u) < 2 * h;
        if (!at_break) {
          EXPECT_NEAR((fd - d[1]).norm(), 0, 1e-5 * (1 + d[1].norm()));
        }
      }
    }
    EXPECT_LE(worst, 1e-12) << "trial " << trial;
    EXPECT_LE(worst_d, 1e-9) << "trial " << trial;
  }
}

TEST(KnotVector, RoundTripsThroughJsonAndOldFilesStillRead) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 8; ++trial) {
    const Surface s = random_surface(3, 2 + trial % 2, trial % 2 == 1, trial % 4 == 3, rng);
    const std::string text = io::surface_to_json_text(s);
    EXPECT_NE(text.find("\"version\":2"), std::string::npos);
    const Surface t = io::surface_from_json_text(text, "mem");
    EXPECT_EQ(t.full_knots_u(), s.full_knots_u());
    EXPECT_EQ(t.full_knots_v(), s.full_knots_v());
    EXPECT_EQ(t.control, s.control);
    EXPECT_EQ(t.evaluate(0.3, 0.7), s.evaluate(0.3, 0.7));
    EXPECT_EQ(io::surface_to_json_text(t), text);
  }
  // A uniform surface is written as before: version 1, no key.
  Surface u;
  u.count_u = u.count_v = 5;
  u.control.assign(25, Point(1, 2, 3));
  const std::string ut = io::surface_to_json_text(u);
  EXPECT_EQ(ut.find("version"), std::string::npos);
  EXPECT_TRUE(io::surface_from_json_text(ut, "mem").knots_u.uniform());
  // A later version, and knots that break the rules, are refused as input data.
  auto j = io::surface_to_json(random_surface(3, 3, false, false, rng));
  auto with = [&](const char* key, nlohmann::json v) {
    auto c = j;
    c[key] = std::move(v);
    return code_of([&] { io::surface_from_json(c, "f.json"); });
  };
  EXPECT_EQ(with("version", 3), ErrorCode::kInputData);
  EXPECT_EQ(with("version", "2"), ErrorCode::kInputData);
  auto k = j["knots_u"];
  std::swap(k[4], k[5]);
  if (k[4] != k[5]) {
    EXPECT_EQ(with("knots_u", k), ErrorCode::kInputData);
  }
  auto z = j["knots_v"];
  z[0] = 1;  // no longer degree + 1 equal end knots
  EXPECT_EQ(with("knots_v", z), ErrorCode::kInputData);
}

TEST(KnotVector, SurfaceRefusesKnotsOfAnotherShape) {
  Surface s;
  s.count_u = 6;
  s.count_v = 5;
  const double b[] = {0, 1, 3};
  EXPECT_EQ(code_of([&] { s.set_knots_u(KnotVector::from_breaks(3, false, b)); }),
            ErrorCode::kUsage);  // 5 control points, not 6
  const double b2[] = {0, 1, 3, 3.5};
  s.set_knots_u(KnotVector::from_breaks(3, false, b2));
  EXPECT_EQ(s.u_end(), 3.5);
}

}  // namespace
}  // namespace sfit
