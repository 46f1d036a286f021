// The surface pictures, checked by what they show: curvature colours of known shapes, the
// straightness of a plane's highlight stripes, the deviation colours against the fit report
// (seams and overlays: surface_picture_overlay_test.cpp).
#include "sfit/render/surface_picture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "picture_checks.h"
#include "sfit/error.h"
#include "sfit/render/colormap.h"
#include "sfit/render/deviations.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit::test {
namespace {

using render::Mode;
using render::Rgb;
constexpr double kPi = std::numbers::pi;

// A patch of the sphere of radius R: polar angle 35 ... 80 degrees, azimuth 0 ... 70 degrees,
// 41 x 41 points. (The fit's clamped ends bend the curvature within about two knot spans of
// the patch's edges, which the picture shows; the checks look at the inside.)
constexpr double kRadius = 2.0;
Rows sphere_patch() {
  return sample_rows(
      [](double s, double t) {
        const double th = (35 + 45 * t) * kPi / 180, ph = 70 * s * kPi / 180;
        return Point(kRadius * std::sin(th) * std::cos(ph), kRadius * std::sin(th) * std::sin(ph),
                     kRadius * std::cos(th));
      },
      std::vector<int>(41, 41));
}

// The view straight onto the patch's middle (azimuth 35 degrees, polar angle 57.5).
render::View onto_sphere_patch() {
  return {90 + 35, 90 - 57.5, 2};
}

TEST(SurfacePicture, SpherePatchGaussianCurvatureIsUniformAndPositive) {
  const FitResult f = fit_at(sphere_patch(), 1e-6);
  render::Scene sc;
  sc.surface = &f.surface;
  render::RenderOptions o = small_options(Mode::kGauss);
  o.view = onto_sphere_patch();
  // K = 1/R^2 sits in the middle of the positive half of the scale: any change shows.
  o.curvature_scale = 2.0 / (kRadius * kRadius);
  const render::RenderResult r = render::render_surface(sc, o);
  dump(r.image, "sphere_gauss");
  const auto inside = interior_pixels(r, 28);
  ASSERT_GT(inside.size(), 5000u);
  // diverging(0.5) = (244, 154, 123) under a light that scales all channels alike.
  const Rgb mid = render::diverging(0.5);
  for (auto [x, y] : inside) {
    const Rgb c = r.image.at(x, y);
    ASSERT_GT(c.r, c.b + 40) << "not red (K > 0) at " << x << "," << y;
    EXPECT_NEAR(double(c.g) / c.r, double(mid.g) / mid.r, 0.03) << x << "," << y;
    EXPECT_NEAR(double(c.b) / c.r, double(mid.b) / mid.r, 0.03) << x << "," << y;
  }
}

TEST(SurfacePicture, SpherePatchMeanCurvatureIsUniform) {
  const FitResult f = fit_at(sphere_patch(), 1e-6);
  render::Scene sc;
  sc.surface = &f.surface;
  render::RenderOptions o = small_options(Mode::kMean);
  o.view = onto_sphere_patch();
  o.curvature_scale = 2 / kRadius;
  const render::RenderResult r = render::render_surface(sc, o);
  dump(r.image, "sphere_mean");
  // |H| = 1/R: the middle of one half of the scale; the sign follows the normal S_u x S_v,
  // here pointing into the sphere (H > 0, red).
  EXPECT_GT(r.value_min * r.value_max, 0) << "one sign all over";
  const auto inside = interior_pixels(r, 28);
  ASSERT_GT(inside.size(), 5000u);
  const Rgb mid = render::diverging(0.5);
  for (auto [x, y] : inside) {
    const Rgb c = r.image.at(x, y);
    ASSERT_GT(c.r, c.b + 40) << x << "," << y;
    EXPECT_NEAR(double(c.g) / c.r, double(mid.g) / mid.r, 0.03) << x << "," << y;
    EXPECT_NEAR(double(c.b) / c.r, double(mid.b) / mid.r, 0.03) << x << "," << y;
  }
}

TEST(SurfacePicture, SaddleGaussianCurvatureIsNegative) {
  // z = (x^2 - y^2) / 2: K = -1 / (1 + x^2 + y^2)^2 < 0 everywhere.
  const Rows rows = sample_rows(
      [](double s, double t) {
        const double x = s - 0.5, y = t - 0.5;
        return Point(x, y, 0.5 * (x * x - y * y));
      },
      std::vector<int>(12, 12));
  const FitResult f = fit_at(rows, 1e-6);
  render::Scene sc;
  sc.surface = &f.surface;
  render::RenderOptions o = small_options(Mode::kGauss);
  o.view = {0, 90, 2};
  const render::RenderResult r = render::render_surface(sc, o);
  EXPECT_LT(r.value_max, 0);
  EXPECT_NEAR(r.value_min, -1.0, 0.02);  // at the centre
  const auto inside = interior_pixels(r);
  ASSERT_GT(inside.size(), 5000u);
  for (auto [x, y] : inside) {
    const Rgb c = r.image.at(x, y);
    ASSERT_GT(c.b, c.r + 20) << "not blue (K < 0) at " << x << "," << y;
  }
}

// Fraction of pixel pairs (p, p + L d(theta)) inside the surface whose stripe colour agrees,
// maximised over the direction theta: 1 for straight parallel stripes. Pixels on a stripe's
// anti-aliased edge (neither dark nor light) are left out.
double best_stripe_agreement(const render::RenderResult& r, double* best_theta) {
  const render::Image& img = r.image;
  std::vector<signed char> bin(static_cast<std::size_t>(img.width) * img.height, -1);
  for (auto [x, y] : interior_pixels(r, 2)) {
    const int gv = img.at(x, y).g;
    if (gv < 60 || gv > 180) bin[y * img.width + x] = gv > 128 ? 1 : 0;
  }
  double best = 0;
  const double L = 40;
  for (int a = 0; a < 720; ++a) {
    const double th = a * kPi / 720, dx = L * std::cos(th), dy = L * std::sin(th);
    long same = 0, all = 0;
    for (int y = 0; y < img.height; y += 2)
      for (int x = 0; x < img.width; x += 2) {
        const int x2 = static_cast<int>(std::lround(x + dx)),
                  y2 = static_cast<int>(std::lround(y + dy));
        if (x2 < 0 || y2 < 0 || x2 >= img.width || y2 >= img.height) continue;
        const int b1 = bin[y * img.width + x], b2 = bin[y2 * img.width + x2];
        if (b1 < 0 || b2 < 0) continue;
        ++all;
        same += b1 == b2;
      }
    if (all > 1000 && double(same) / all > best) {
      best = double(same) / all;
      *best_theta = th;
    }
  }
  return best;
}

TEST(SurfacePicture, PlaneZebraStripesAreStraightAndParallel) {
  const Rows rows = sample_rows([](double s, double t) { return Point(s, t, 0.3 * s + 0.2 * t); },
                                std::vector<int>(6, 6));
  const FitResult f = fit_at(rows, 1e-6);
  render::Scene sc;
  sc.surface = &f.surface;
  render::RenderOptions o = small_options(Mode::kZebra);
  o.view = {30, 60, 2};
  const render::RenderResult r = render::render_surface(sc, o);
  dump(r.image, "plane_zebra");
  double theta = 0;
  const double agree = best_stripe_agreement(r, &theta);
  EXPECT_GT(agree, 0.995) << "stripes are not straight and parallel";
  RecordProperty("agreement", std::to_string(agree));
  // Across the stripes: several of them, evenly spaced.
  const auto inside = interior_pixels(r, 2);
  double cx = 0, cy = 0;
  for (auto [x, y] : inside) cx += x, cy += y;
  cx /= inside.size();
  cy /= inside.size();
  const double nx = -std::sin(theta), ny = std::cos(theta);
  // Edges where the (bilinearly interpolated) green channel crosses mid-grey, to a fraction
  // of a pixel.
  auto green = [&](double x, double y, bool* ok) {
    const int x0 = static_cast<int>(std::floor(x - 0.5)),
              y0 = static_cast<int>(std::floor(y - 0.5));
    const double fx = x - 0.5 - x0, fy = y - 0.5 - y0;
    double v = 0;
    *ok = true;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        if (!r.image.contains(x0 + i, y0 + j) || is_background(r.image.at(x0 + i, y0 + j))) {
          *ok = false;
          return 0.0;
        }
        v += (i ? fx : 1 - fx) * (j ? fy : 1 - fy) * r.image.at(x0 + i, y0 + j).g;
      }
    return v;
  };
  std::vector<double> edges;
  double prev_s = NAN, prev_v = NAN;
  for (double s = -400; s <= 400; s += 0.1) {
    bool ok = false;
    const double v = green(cx + s * nx, cy + s * ny, &ok);
    if (!ok) {
      prev_s = NAN;
      continue;
    }
    if (!std::isnan(prev_s) && (prev_v - 128) * (v - 128) < 0)
      edges.push_back(prev_s + (s - prev_s) * (128 - prev_v) / (v - prev_v));
    prev_s = s;
    prev_v = v;
  }
  ASSERT_GE(edges.size(), 8u);
  std::vector<double> widths;
  for (std::size_t i = 2; i + 1 < edges.size(); ++i) widths.push_back(edges[i] - edges[i - 1]);
  const auto [lo, hi] = std::minmax_element(widths.begin(), widths.end());
  EXPECT_LT(*hi / *lo, 1.2) << "stripe widths vary too much";
}

TEST(SurfacePicture, CurvedZebraStripesAreNotStraight) {
  // The same measure on a gently curved surface in the same view: the stripes bend, so the
  // plane's result means something.
  const Rows rows = sample_rows(
      [](double s, double t) { return Point(s, t, 0.3 * s + 0.2 * t + 0.4 * (s * s - t * t)); },
      std::vector<int>(9, 9));
  const FitResult f = fit_at(rows, 1e-6);
  render::Scene sc;
  sc.surface = &f.surface;
  render::RenderOptions o = small_options(Mode::kZebra);
  o.view = {30, 60, 2};
  const render::RenderResult r = render::render_surface(sc, o);
  dump(r.image, "saddle_zebra");
  double theta = 0;
  const double agree = best_stripe_agreement(r, &theta);
  RecordProperty("agreement", std::to_string(agree));
  EXPECT_LT(agree, 0.95);
}

double max_ratio_of_report(const FitReport& rep) {
  double m = 0;
  for (int a = 0; a < 3; ++a) m = std::max(m, rep.max_deviation[a] / rep.tolerance[a]);
  return m;
}

TEST(SurfacePicture, DeviationColoursMatchTheReportsWorstPoint) {
  const Rows rows = load_rows(example("ship_px121_stations.rows"));
  const FitResult f = fit_at(rows, 0.2);
  const std::vector<Point> d =
      render::deviations_at_parameters(f.surface, rows, f.u, f.v_for_points());
  render::Scene sc;
  sc.surface = &f.surface;
  sc.rows = &rows;
  sc.deviations = d;
  sc.tolerance = f.report.tolerance;
  render::RenderOptions o = small_options(Mode::kDeviation);
  o.view = {135, 25, 2};
  const render::RenderResult r = render::render_surface(sc, o);
  const double want = max_ratio_of_report(f.report);
  ASSERT_GT(want, 0.3);
  EXPECT_NEAR(r.worst_ratio, want, 1e-9);
  const long worst = static_cast<long>(rows.offsets()[f.report.worst_row]) + f.report.worst_index;
  EXPECT_EQ(r.worst_point, worst);
  // The worst point's disc shows the report's ratio.
  const Eigen::Vector3d p = r.camera.project(rows.points()[worst]);
  double dist = 0;
  const double t = decode_sequential(r.image.at(int(p.x()), int(p.y())), &dist);
  EXPECT_LT(dist, 4.0);
  EXPECT_NEAR(t, want, 0.02);
  // No visible point shows more.
  for (std::size_t k = 0; k < rows.total_points(); ++k) {
    const Eigen::Vector3d q = r.camera.project(rows.points()[k]);
    double dk = 0;
    const double tk = decode_sequential(r.image.at(int(q.x()), int(q.y())), &dk);
    if (dk < 4.0) {
      EXPECT_LE(tk, want + 0.02) << "point " << k;
    }
  }
  // The colour bar runs from sequential(0) at the bottom to sequential(1) = T at the top.
  const int bx = (r.bar_x0 + r.bar_x1) / 2;
  EXPECT_NEAR(decode_sequential(r.image.at(bx, r.bar_y0)), 1.0, 0.005);
  EXPECT_NEAR(decode_sequential(r.image.at(bx, r.bar_y1 - 1)), 0.0, 0.005);
}

TEST(SurfacePicture, PointsBeyondTheToleranceAreMagenta) {
  const Rows rows = load_rows(example("ship_px121_stations.rows"));
  const FitResult f = fit_at(rows, 0.2);
  std::vector<Point> d = render::deviations_at_parameters(f.surface, rows, f.u, f.v_for_points());
  d[40] = Point(0, 0.5, 0);  // 2.5 T
  render::Scene sc;
  sc.surface = &f.surface;
  sc.rows = &rows;
  sc.deviations = d;
  sc.tolerance = f.report.tolerance;
  render::RenderOptions o = small_options(Mode::kDeviation);
  const render::RenderResult r = render::render_surface(sc, o);
  EXPECT_EQ(r.worst_point, 40);
  EXPECT_NEAR(r.worst_ratio, 2.5, 1e-12);
  const Eigen::Vector3d p = r.camera.project(rows.points()[40]);
  EXPECT_EQ(r.image.at(int(p.x()), int(p.y())), render::kExceeded);
}

}  // namespace
}  // namespace sfit::test
