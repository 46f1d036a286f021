// Normal orientation (orient(), make_mesh()): closed surfaces outward, height fields up, the
// winding with the normals, flip the opposite, uv as the data runs.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "exchange_cases.h"
#include "sfit/error.h"
#include "sfit/exchange/tessellate.h"
#include "sfit/exchange/writers.h"
#include "test_support.h"

namespace sfit::exchange {
namespace {

// Six times the volume of the triangles, centred: for a closed mesh the enclosed volume,
// positive when the triangles wind counter-clockwise seen from outside.
double signed_volume(const Mesh& m) {
  Point c = Point::Zero();
  for (const Point& p : m.vertices) c += p;
  c /= static_cast<double>(m.vertices.size());
  double v = 0;
  for (const auto& t : m.triangles)
    v += (m.vertices[t[0]] - c).dot((m.vertices[t[1]] - c).cross(m.vertices[t[2]] - c));
  return v;
}

// Fraction of triangles wound counter-clockwise about the mean of their vertex normals.
double winding_agreement(const Mesh& m) {
  std::size_t good = 0;
  for (const auto& t : m.triangles) {
    const Point f =
        (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    if (f.dot(m.normals[t[0]] + m.normals[t[1]] + m.normals[t[2]]) > 0) ++good;
  }
  return static_cast<double>(good) / static_cast<double>(m.triangles.size());
}

// A torus fitted from rows whose data direction gives inward normals.
FitResult inward_torus() {
  const double pi = 3.14159265358979323846;
  const Rows rows = test::sample_rows(
      [&](double s, double t) {
        const double a = 2 * pi * s, b = 2 * pi * t;
        return Point((2 + 0.5 * std::cos(a)) * std::cos(b), (2 + 0.5 * std::cos(a)) * std::sin(b),
                     0.5 * std::sin(a));
      },
      std::vector<int>(16, 20), true, true);
  FitOptions o;
  o.closed_u = o.closed_v = true;
  o.tolerance = relative_tolerance(rows, 1e-3);
  return fit_surface(rows, o);
}

// z = f(x, y) with the rows running towards -y: the data direction points down.
FitResult downward_height_field() {
  const Rows rows = test::sample_rows(
      [](double s, double t) {
        const double x = 2 * s - 1, y = 1 - 2 * t;
        return Point(x, y, 0.6 * std::exp(-3 * (x * x + y * y)));
      },
      std::vector<int>(15, 20));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  return fit_surface(rows, o);
}

TEST(Orient, ClosedSurfacesPointOutwardWhateverTheDataDirection) {
  const FitResult torus = inward_torus();
  Mesh m = tessellate(torus.surface, 30, 20);
  ASSERT_LT(signed_volume(m), 0) << "the test's torus should run inward";
  orient(m, NormalRule::kAuto);
  EXPECT_TRUE(m.flipped);
  EXPECT_GT(signed_volume(m), 0);
  EXPECT_GE(winding_agreement(m), 0.999);
  EXPECT_EQ(m.orientation, "outward (closed in u and v)");
  // Every bundled closed case: outward (its capped volume), wound with its normals.
  for (const auto* c : test::must_pass_cases()) {
    if (!c->closed_u && !c->closed_v) continue;
    SCOPED_TRACE(c->name);
    const Mesh a =
        make_mesh(c->fit.surface, 0, c->fit.report.tolerance.minCoeff(), NormalRule::kAuto);
    const Mesh f =
        make_mesh(c->fit.surface, 0, c->fit.report.tolerance.minCoeff(), NormalRule::kFlip);
    EXPECT_NE(a.flipped, f.flipped);
    EXPECT_GE(winding_agreement(a), 0.99);
    EXPECT_GE(winding_agreement(f), 0.99);
    // Outward: the normals point away from the centre of the sample points on average.
    Point c0 = Point::Zero();
    for (const Point& p : a.vertices) c0 += p;
    c0 /= static_cast<double>(a.vertices.size());
    double away = 0;
    for (std::size_t k = 0; k < a.vertices.size(); ++k)
      away += a.normals[k].dot(a.vertices[k] - c0);
    EXPECT_GT(away, 0);
  }
}

TEST(Orient, HeightFieldsPointUp) {
  const FitResult h = downward_height_field();
  Mesh m = tessellate(h.surface, 25, 25);
  ASSERT_LT(m.normals[0].z(), 0) << "the test's height field should run down";
  orient(m, NormalRule::kAuto);
  for (const Point& n : m.normals) EXPECT_GT(n.z(), 0);
  for (const auto& t : m.triangles)
    EXPECT_GT((m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).z(),
              0);
  EXPECT_EQ(m.orientation, "up (+z, a height field)");
  orient(m, NormalRule::kFlip);
  for (const Point& n : m.normals) EXPECT_LT(n.z(), 0);
  EXPECT_GE(winding_agreement(m), 0.999);
  // uv: back to the data's S_u x S_v, as tessellate() gives it, whatever came before.
  orient(m, NormalRule::kData);
  const Mesh raw = tessellate(h.surface, 25, 25);
  EXPECT_FALSE(m.flipped);
  EXPECT_EQ(m.normals, raw.normals);
  EXPECT_EQ(m.triangles, raw.triangles);
}

TEST(Orient, OtherOpenSurfacesKeepTheDataDirection) {
  const auto* ship = test::must_pass_cases()[0];  // open, with vertical sides: not a graph
  Mesh m = tessellate(ship->fit.surface, 20, 20);
  const Mesh raw = m;
  orient(m, NormalRule::kAuto);
  EXPECT_EQ(m.orientation, "as the data runs (S_u x S_v)");
  EXPECT_EQ(m.normals, raw.normals);
}

TEST(Orient, RuleNamesAndDensityAreCheckedByTheLibrary) {
  EXPECT_EQ(parse_normal_rule("auto"), NormalRule::kAuto);
  EXPECT_EQ(parse_normal_rule("flip"), NormalRule::kFlip);
  EXPECT_EQ(parse_normal_rule("uv"), NormalRule::kData);
  for (const char* bad : {"", "out", "Auto"}) {
    try {
      parse_normal_rule(bad);
      FAIL() << bad;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kUsage);
      EXPECT_EQ(e.place().option, "--normals");
    }
  }
  check_mesh_density(0);
  check_mesh_density(3);
  check_mesh_density(kMaxMeshDensity);
  for (int bad : {-1, 1, 2, kMaxMeshDensity + 1, 100000})
    EXPECT_THROW(check_mesh_density(bad), Error) << bad;
}

}  // namespace
}  // namespace sfit::exchange
