#include "sfit/exchange/tessellate.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "exchange_cases.h"
#include "sfit/error.h"

namespace sfit::exchange {
namespace {

// Whether the surface closes along u (along v with `along_v`), by the test's own reading:
// periodic, or clamped with its first and last control-point columns (rows) equal (closed
// corner knots: a crease at the seam). A mesh wraps such a direction.
bool closes(const Surface& s, bool along_v) {
  if (along_v ? s.periodic_v : s.periodic_u) return true;
  for (int k = 0; k < (along_v ? s.count_u : s.count_v); ++k) {
    const int first = along_v ? k * s.count_v : k;
    const int last = along_v ? first + s.count_v - 1 : (s.count_u - 1) * s.count_v + k;
    if (s.control[static_cast<std::size_t>(first)] != s.control[static_cast<std::size_t>(last)])
      return false;
  }
  return true;
}

// z = x^2 + y^2 over [0, 1]^2 as one biquadratic Bezier patch (u = x, v = y).
Surface paraboloid() {
  Surface s;
  s.degree_u = s.degree_v = 2;
  s.count_u = s.count_v = 3;
  const double a[3] = {0, 0, 1};  // Bezier coefficients of t^2
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s.control.emplace_back(i / 2.0, j / 2.0, a[i] + a[j]);
  return s;
}

TEST(Tessellate, CountsFollowTheTopology) {
  for (const auto* c : test::must_pass_cases()) {
    SCOPED_TRACE(c->name);
    const Surface& s = c->fit.surface;
    const Mesh m = tessellate(s, 7, 5);
    EXPECT_EQ(m.vertices.size(), 35u);
    EXPECT_EQ(m.normals.size(), 35u);
    const std::size_t qu = closes(s, false) ? 7 : 6, qv = closes(s, true) ? 5 : 4;
    EXPECT_EQ(m.triangles.size(), 2 * qu * qv);
    // Vertex (a, b) is S(u_a, v_b); the last open sample is the domain end.
    EXPECT_LE((m.vertices[m.index(3, 2)] - s.evaluate(m.u[3], m.v[2])).norm(), 1e-14 * c->diagonal);
    EXPECT_EQ(m.u.back(), closes(s, false) ? s.u_end() * 6 / 7 : s.u_end());
  }
}

// Each edge of a closed direction is shared by exactly two triangles: no crack at the seam.
TEST(Tessellate, ClosedDirectionsAreWatertight) {
  for (const auto* c : test::must_pass_cases()) {
    SCOPED_TRACE(c->name);
    const Surface& s = c->fit.surface;
    const Mesh m = tessellate(s, 12, 9);
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k) {
        auto a = t[k], b = t[(k + 1) % 3];
        ++edges[{std::min(a, b), std::max(a, b)}];
      }
    std::size_t boundary = 0;
    for (const auto& [e, n] : edges) {
      EXPECT_LE(n, 2);
      if (n == 1) ++boundary;
    }
    // Open ends only: the u = 0 and u = end columns have quads_v edges each, the v ends quads_u.
    const std::size_t want =
        (closes(s, false) ? 0 : 2 * m.quads_v()) + (closes(s, true) ? 0 : 2 * m.quads_u());
    EXPECT_EQ(boundary, want);
    if (closes(s, false) && closes(s, true)) {
      EXPECT_EQ(boundary, 0u);
    }
  }
}

// The mesh at the default density stays within the chordal error it promises: measured at
// every triangle's edge midpoints and centroid against the surface at the same parameters.
TEST(Tessellate, DefaultDensityHoldsTheChordalError) {
  for (const auto& c : test::fitted_cases()) {
    if (!c.bundled && c.name != "data/ring_body" && c.name != "data/height_field_small") continue;
    SCOPED_TRACE(c.name);
    const Surface& s = c.fit.surface;
    const double T = c.fit.report.tolerance.minCoeff();
    const double chord = default_chord(s, T);
    EXPECT_EQ(chord, T / 4);
    const Density d = choose_density(s, chord);
    EXPECT_LE(d.bound, chord);
    const Mesh m = tessellate(s, d.samples_u, d.samples_v);
    double worst = 0;
    for (int b = 0; b < m.quads_v(); ++b)
      for (int a = 0; a < m.quads_u(); ++a) {
        const double u0 = m.u[a], v0 = m.v[b];
        const double u1 = a + 1 < m.samples_u ? m.u[a + 1] : s.u_end();
        const double v1 = b + 1 < m.samples_v ? m.v[b + 1] : s.v_end();
        const Point p00 = m.vertices[m.index(a, b)], p10 = m.vertices[m.index(a + 1, b)],
                    p11 = m.vertices[m.index(a + 1, b + 1)], p01 = m.vertices[m.index(a, b + 1)];
        // Triangles (00, 10, 11) and (00, 11, 01): linear interpolation in (u, v).
        auto check = [&](double fu, double fv, const Point& lin) {
          worst =
              std::max(worst, (s.evaluate(u0 + fu * (u1 - u0), v0 + fv * (v1 - v0)) - lin).norm());
        };
        check(0.5, 0, (p00 + p10) / 2);
        check(1, 0.5, (p10 + p11) / 2);
        check(0.5, 0.5, (p00 + p11) / 2);
        check(0, 0.5, (p00 + p01) / 2);
        check(0.5, 1, (p01 + p11) / 2);
        check(2.0 / 3, 1.0 / 3, (p00 + p10 + p11) / 3);
        check(1.0 / 3, 2.0 / 3, (p00 + p11 + p01) / 3);
      }
    EXPECT_LE(worst, chord);
    std::printf("[ measure  ] %-26s mesh %4d x %4d, %7zu triangles, chordal error %.3g = %.2f T\n",
                c.name.c_str(), d.samples_u, d.samples_v, m.triangles.size(), worst, worst / T);
  }
}

TEST(Tessellate, NormalsAreUnitAndFollowSuCrossSv) {
  for (const auto* c : test::must_pass_cases()) {
    SCOPED_TRACE(c->name);
    const Surface& s = c->fit.surface;
    const Mesh m = tessellate(s, 20, 15);
    for (int b = 0; b < m.samples_v; ++b)
      for (int a = 0; a < m.samples_u; ++a) {
        const Point& n = m.normals[m.index(a, b)];
        EXPECT_NEAR(n.norm(), 1.0, 1e-12);
        Point d[6];
        s.derivatives(m.u[a], m.v[b], d);
        const Point x = d[1].cross(d[2]);
        if (x.norm() > 1e-6 * d[1].norm() * d[2].norm()) {
          EXPECT_GT(n.dot(x), 0);
        }
      }
    // Triangles wind counter-clockwise about the normals (at the default density: a coarse
    // mesh of a sharp leading edge may fold).
    const Density dd = choose_density(s, default_chord(s, c->fit.report.tolerance.minCoeff()));
    const Mesh fine = tessellate(s, dd.samples_u, dd.samples_v);
    // A vertex on a crease (a knot of multiplicity >= degree along u: corner knots' seam) has
    // a one-sided normal: its triangles are not counted.
    std::vector<double> at;
    std::vector<int> mult;
    s.knots_u.breaks(at, mult);
    auto on_crease = [&](std::uint32_t k) {
      const double u = fine.u[k % static_cast<std::uint32_t>(fine.samples_u)];
      for (std::size_t i = 0; i < at.size(); ++i)
        if (mult[i] >= s.degree_u && std::abs(u - at[i]) <= 1e-12 * s.u_end()) return true;
      return false;
    };
    std::size_t agree = 0, counted = 0;
    for (const auto& t : fine.triangles) {
      if (closes(s, false) && (on_crease(t[0]) || on_crease(t[1]) || on_crease(t[2]))) continue;
      ++counted;
      const Point f = (fine.vertices[t[1]] - fine.vertices[t[0]])
                          .cross(fine.vertices[t[2]] - fine.vertices[t[0]]);
      if (f.dot(fine.normals[t[0]] + fine.normals[t[1]] + fine.normals[t[2]]) > 0) ++agree;
    }
    // All but a few: on the fitted blade 64 of 48384 triangles wind against the mean of
    // their vertex normals, where the normal turns sharply within one cell.
    EXPECT_GE(agree, counted - counted / 500);
  }
}

TEST(Tessellate, CurvatureOfAParaboloid) {
  const Surface s = paraboloid();
  EXPECT_NEAR(s.evaluate(0.5, 0.5).z(), 0.5, 1e-15);
  const Curvature k = curvature(s, 0, 0);  // z = x^2 + y^2 at the apex: H = 2, K = 4
  EXPECT_NEAR(k.mean, 2.0, 1e-12);
  EXPECT_NEAR(k.gaussian, 4.0, 1e-12);
  // Away from the apex, K = 4 / (1 + 4 r^2)^2.
  const Curvature k2 = curvature(s, 0.5, 0.25);
  const double r2 = 0.25 + 0.0625;
  EXPECT_NEAR(k2.gaussian, 4 / std::pow(1 + 4 * r2, 2), 1e-12);
  // A flat surface: the density is the minimum (4 per span) and the bound is 0.
  Surface flat = s;
  for (auto& p : flat.control) p.z() = 0;
  const Density d = choose_density(flat, 1e-6);
  EXPECT_EQ(d.samples_u, 5);
  EXPECT_EQ(d.bound, 0);
  EXPECT_EQ(curvature(flat, 0.3, 0.3).gaussian, 0);
}

TEST(Tessellate, DensityShrinksWithTheSquareRootOfTheChord) {
  const Surface s = paraboloid();
  const Density a = choose_density(s, 1e-4), b = choose_density(s, 1e-6);
  EXPECT_NEAR(static_cast<double>(b.samples_u - 1) / (a.samples_u - 1), 10.0, 0.2);
  EXPECT_LE(a.bound, 1e-4);
  EXPECT_LE(b.bound, 1e-6);
  const Density capped = choose_density(s, 1e-16, 100);
  EXPECT_EQ(capped.samples_u, 100);
  EXPECT_GT(capped.bound, 1e-16);  // the cap is honest about what it gives
}

TEST(Tessellate, RefusesBadDensities) {
  const Surface s = paraboloid();
  for (auto [nu, nv] : {std::pair{1, 5}, {5, 0}, {-3, 4}, {200000, 2}}) {
    try {
      tessellate(s, nu, nv);
      FAIL() << nu << " x " << nv;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kUsage);
      EXPECT_EQ(e.place().option, "--mesh-density");
    }
  }
}

}  // namespace
}  // namespace sfit::exchange

namespace sfit::exchange {
namespace {

// The writers' default mesh: the chordal target where it fits, coarsened evenly to the
// triangle budget where it does not, and honest about the bound it then holds.
TEST(Tessellate, DefaultMeshKeepsTheTriangleBudget) {
  for (const auto& c : test::fitted_cases()) {
    SCOPED_TRACE(c.name);
    const Surface& s = c.fit.surface;
    const double T = c.fit.report.tolerance.minCoeff();
    const Mesh m = make_mesh(s, 0, T, NormalRule::kAuto);
    EXPECT_LE(static_cast<double>(m.triangles.size()), kDefaultTriangleBudget);
    const Density target = choose_density(s, default_chord(s, T));
    const double wanted =
        2.0 * (target.samples_u - !closes(s, false)) * (target.samples_v - !closes(s, true));
    if (wanted <= kDefaultTriangleBudget) {
      EXPECT_EQ(m.samples_u, target.samples_u);  // fits: the chordal target is kept
      EXPECT_EQ(m.samples_v, target.samples_v);
      EXPECT_LE(m.chordal_bound, T / 4);
    } else {
      EXPECT_GT(m.chordal_bound, T / 4);  // coarser, and says so
      EXPECT_GE(static_cast<double>(m.triangles.size()), 0.9 * kDefaultTriangleBudget);
    }
    std::printf(
        "[ measure  ] %-26s %3d x %3d control points: default mesh %4d x %4d, %6zu "
        "triangles (target %4d x %4d), chordal bound %.3g T\n",
        c.name.c_str(), s.count_u, s.count_v, m.samples_u, m.samples_v, m.triangles.size(),
        target.samples_u, target.samples_v, m.chordal_bound / T);
  }
  // A 16 x 62 control net of a wavy hull at a tight chord: the budget, not 1.2 million.
  Surface hull;
  hull.count_u = 16;
  hull.count_v = 62;
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 62; ++j)
      hull.control.emplace_back(j, 3 * std::sin(0.2 * i) + 0.1 * std::sin(j), i * 0.5);
  const Density full = choose_density(hull, 1e-4);
  const Density capped = choose_density(hull, 1e-4, 4096, kDefaultTriangleBudget);
  EXPECT_GT(2.0 * (full.samples_u - 1) * (full.samples_v - 1), kDefaultTriangleBudget);
  EXPECT_LE(2.0 * (capped.samples_u - 1) * (capped.samples_v - 1), kDefaultTriangleBudget);
  EXPECT_GT(capped.bound, full.bound);
  std::printf(
      "[ measure  ] 16 x 62 hull at chord 1e-4: %d x %d samples unbounded, %d x %d within "
      "the budget (bound %.3g)\n",
      full.samples_u, full.samples_v, capped.samples_u, capped.samples_v, capped.bound);
  // Coarsened evenly: the aspect of the cells stays.
  EXPECT_NEAR(static_cast<double>(capped.samples_u - 1) / (capped.samples_v - 1),
              static_cast<double>(full.samples_u - 1) / (full.samples_v - 1), 0.1);
}

}  // namespace
}  // namespace sfit::exchange
