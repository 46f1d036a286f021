// Numerical extremes: offsets and scales, the highest degree, very long rows, very
// many rows, interpolation of ragged rows, a tolerance larger than the data. In every case
// the surface must be finite and hold every point within tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit::test {
namespace {

Point wave(double s, double t) {
  return Point(2.0 * s, 1.5 * t + 0.1 * s * s, 0.3 * std::sin(3.0 * s) * std::cos(2.0 * t));
}

void expect_sound(const FitResult& r, const char* what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(r.surface.control.size(),
            static_cast<std::size_t>(r.surface.count_u) * r.surface.count_v);
  for (const Point& p : r.surface.control) ASSERT_TRUE(p.allFinite()) << p.transpose();
  EXPECT_TRUE(r.report.within_tolerance);
  EXPECT_TRUE(r.report.max_deviation.allFinite());
  for (int a = 0; a < 3; ++a)
    EXPECT_LE(r.report.max_deviation[a], r.report.tolerance[a] + r.report.roundoff) << a;
}

Rows mapped(const Rows& rows, double scale, const Point& offset) {
  Rows out;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (const Point& p : rows[j]) out.push_point(scale * p + offset);
    out.end_row();
  }
  return out;
}

// x -> s x + b maps the data, the tolerance (times s) and so the surface: same counts, and
// control points that agree up to the map, to a precision set by the data's own rounding.
TEST(Extremes, AffineMapOfTheDataMapsTheSurface) {
  const Rows base = sample_rows(wave, {14, 17, 11, 16, 13, 15, 12});
  FitOptions o;
  o.tolerance = Point(2e-3, 2e-3, 1e-3);
  const FitResult ref = fit_surface(base, o);
  expect_sound(ref, "reference");
  const double size = bounding_box(base).diagonal();
  struct Map {
    double scale;
    Point offset;
    double digits;  // relative agreement expected, from the rounding of scale * x + offset
  };
  const std::vector<Map> maps = {
      {1.0, Point(1e7, -1e7, 1e7), 1e-8},   // offset 1e7: data rounded to ~2e-9 absolute
      {1e-6, Point::Zero(), 1e-11},         // scale 1e-6
      {1e6, Point::Zero(), 1e-11},          // scale 1e6
      {1e6, Point(1e7, 2e7, -3e7), 1e-11},  // scale 1e6 and offset 1e7
      {1e-3, Point(1e3, 1e3, 1e3), 1e-9},   // millimetres to metres, shifted: ulp(1e3) / size
  };
  for (const Map& m : maps) {
    SCOPED_TRACE(::testing::Message() << "scale " << m.scale << " offset " << m.offset.transpose());
    FitOptions om = o;
    om.tolerance = m.scale * o.tolerance;
    const FitResult r = fit_surface(mapped(base, m.scale, m.offset), om);
    expect_sound(r, "mapped");
    ASSERT_EQ(r.surface.count_u, ref.surface.count_u);
    ASSERT_EQ(r.surface.count_v, ref.surface.count_v);
    EXPECT_EQ(r.report.row_counts, ref.report.row_counts);
    EXPECT_EQ(r.report.column_counts, ref.report.column_counts);
    double worst = 0;
    for (std::size_t k = 0; k < r.surface.control.size(); ++k) {
      const Point expected = m.scale * ref.surface.control[k] + m.offset;
      worst = std::max(worst, (r.surface.control[k] - expected).cwiseAbs().maxCoeff());
    }
    EXPECT_LE(worst, m.digits * m.scale * size) << "worst control-point difference " << worst;
    // And the parameters are those of the reference: exactly where the rule reads the rows'
    // indices or lengths; the geometric rule projects the points, so its parameters carry the
    // data's rounding (digits), as the control points do.
    ASSERT_EQ(r.report.parametrization, ref.report.parametrization);
    const bool projected = ref.report.parametrization == Parametrization::kGeometric;
    ASSERT_EQ(r.u.size(), ref.u.size());
    ASSERT_EQ(r.v_points.size(), ref.v_points.size());
    for (std::size_t k = 0; k < r.u.size(); ++k)
      EXPECT_NEAR(r.u[k], ref.u[k], projected ? 10 * m.digits * (1 + std::abs(ref.u[k])) : 1e-12);
    for (std::size_t k = 0; k < r.v_points.size(); ++k)
      EXPECT_NEAR(r.v_points[k], ref.v_points[k], 10 * m.digits * (1 + std::abs(ref.v_points[k])));
  }
}

TEST(Extremes, DegreeTwentyInBothDirections) {
  const Rows rows = sample_rows(wave, std::vector<int>(25, 30));
  for (double tol : {1e-4, 0.0}) {
    FitOptions o;
    o.degree_u = o.degree_v = 20;
    o.tolerance = Point::Constant(tol);
    const FitResult r = fit_surface(rows, o);
    expect_sound(r, tol == 0 ? "T = 0" : "T = 1e-4");
    EXPECT_GE(r.surface.count_u, 21);
    EXPECT_GE(r.surface.count_v, 21);
    EXPECT_EQ(r.surface.degree_u, 20);
  }
}

TEST(Extremes, OneRowOfAMillionPoints) {
#if defined(__SANITIZE_ADDRESS__)
  // The same paths at a fifth of the size: AddressSanitizer runs this case 7x slower (164 s
  // on 2 cores), the release suite runs it at full size.
  const int n = 200000;
#else
  const int n = 1000000;
#endif
  const Rows rows = sample_rows(wave, {n, 40, 1000});
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-4);
  const FitResult r = fit_surface(rows, o);
  expect_sound(r, "a row of 10^6 points (2 10^5 under AddressSanitizer)");
  EXPECT_EQ(r.report.points, static_cast<std::size_t>(n) + 1040u);
  EXPECT_EQ(r.u.size(), static_cast<std::size_t>(n) + 1040u);
}

TEST(Extremes, HundredThousandRowsOfThreePoints) {
#if defined(__SANITIZE_ADDRESS__)
  const std::size_t m = 20000;  // the same paths: AddressSanitizer takes 61 s at 10^5 rows
#else
  const std::size_t m = 100000;
#endif
  const Rows rows = sample_rows(wave, std::vector<int>(m, 3));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-4);
  const FitResult r = fit_surface(rows, o);
  expect_sound(r, "10^5 rows of 3 (2 10^4 under AddressSanitizer)");
  EXPECT_EQ(r.report.rows, m);
  EXPECT_EQ(r.surface.count_u, 4);  // 3 points per row: re-represented at order 4, count 4
}

TEST(Extremes, ToleranceZeroWithRaggedRowsInterpolates) {
  for (bool closed_u : {false, true}) {
    SCOPED_TRACE(closed_u ? "closed rows" : "open rows");
    const Rows rows = sample_rows(wave, {7, 3, 12, 1, 9, 4, 15}, closed_u);
    FitOptions o;
    o.closed_u = closed_u;
    const FitResult r = fit_surface(rows, o);  // tolerance 0
    expect_sound(r, "T = 0");
    for (int a = 0; a < 3; ++a) EXPECT_LE(r.report.max_deviation[a], r.report.roundoff);
  }
}

TEST(Extremes, ToleranceFarLargerThanTheDataGivesOneBezierPatch) {
  const Rows rows = sample_rows(wave, {30, 25, 40, 33, 28, 35});
  for (int p : {1, 2, 3, 5}) {
    FitOptions o;
    o.degree_u = p;
    o.degree_v = p + 1;
    o.tolerance = Point::Constant(1e3 * bounding_box(rows).diagonal());
    const FitResult r = fit_surface(rows, o);
    expect_sound(r, "T >> data");
    EXPECT_EQ(r.surface.count_u, p + 1);
    EXPECT_EQ(r.surface.count_v, p + 2);
  }
}

}  // namespace
}  // namespace sfit::test
