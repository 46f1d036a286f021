// The surface pictures, checked by what they show: closed surfaces drawn without a seam, the
// overlays (control net, data points, row curves), and the options a picture refuses.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "picture_checks.h"
#include "sfit/error.h"
#include "sfit/render/surface_picture.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit::test {
namespace {

using render::Mode;
using render::Rgb;
constexpr double kPi = std::numbers::pi;

// Brightness of a pixel.
double grey(Rgb c) {
  return (c.r + c.g + c.b) / 3.0;
}

// A flat annulus 1 <= r <= 1.5 in z = 0, seen from above: nothing lies behind it, so a crack
// anywhere, the seam included, would show the white background.
long background_inside_annulus(const render::RenderResult& r) {
  const Eigen::Vector3d c = r.camera.project(Point(0, 0, 0));
  const double px = r.camera.scale;  // pixels per unit length
  long gaps = 0;
  for (int y = 0; y < r.image.height; ++y)
    for (int x = 0; x < r.image.width; ++x) {
      const double rho = std::hypot(x + 0.5 - c.x(), y + 0.5 - c.y()) / px;
      if (rho > 1 + 2 / px && rho < 1.5 - 2 / px) gaps += is_background(r.image.at(x, y));
    }
  return gaps;
}

Point on_annulus(double angle, double radial) {
  const double rho = 1 + 0.5 * radial;
  return Point(rho * std::cos(angle), rho * std::sin(angle), 0);
}

TEST(SurfacePicture, ClosedRowsRenderWithoutASeamGap) {
  // Rows are circles: closed in u, the seam along the positive x axis.
  const Rows rows = sample_rows([](double s, double t) { return on_annulus(2 * kPi * s, t); },
                                std::vector<int>(5, 24), true, false);
  const FitResult f = fit_at(rows, 1e-4, true, false);
  ASSERT_TRUE(f.surface.periodic_u);
  render::Scene sc;
  sc.surface = &f.surface;
  for (const Mode m : {Mode::kShaded, Mode::kZebra}) {
    render::RenderOptions o = small_options(m);
    o.view = {0, 90, 2};
    EXPECT_EQ(background_inside_annulus(render::render_surface(sc, o)), 0) << render::to_string(m);
  }
}

TEST(SurfacePicture, ClosedRowSequenceRendersWithoutASeamGap) {
  // Rows are radial segments around the circle: closed in v.
  const Rows rows = sample_rows([](double s, double t) { return on_annulus(2 * kPi * t, s); },
                                std::vector<int>(24, 5), false, true);
  const FitResult f = fit_at(rows, 1e-4, false, true);
  ASSERT_TRUE(f.surface.periodic_v);
  render::Scene sc;
  sc.surface = &f.surface;
  render::RenderOptions o = small_options(Mode::kShaded);
  o.view = {0, 90, 2};
  EXPECT_EQ(background_inside_annulus(render::render_surface(sc, o)), 0);
}

TEST(SurfacePicture, ClosedCylinderShowsNoLineAtItsSeam) {
  // Rows are circles starting at the point that faces the viewer (-y): the u seam runs down
  // the middle of the picture; the exact normals make it invisible.
  const Rows rows = sample_rows(
      [](double s, double t) {
        const double a = -kPi / 2 + 2 * kPi * s;
        return Point(std::cos(a), std::sin(a), 2 * t);
      },
      std::vector<int>(5, 24), true, false);
  const FitResult f = fit_at(rows, 1e-4, true, false);
  render::Scene sc;
  sc.surface = &f.surface;
  render::RenderOptions o = small_options(Mode::kShaded);
  o.view = {0, 0, 2};
  const render::RenderResult r = render::render_surface(sc, o);
  const Eigen::Vector3d lo = r.camera.project(Point(-1, 0, 0)),
                        hi = r.camera.project(Point(1, 0, 2));
  const int sx = static_cast<int>(r.camera.project(Point(0, -1, 1)).x());
  double worst = 0;
  long gaps = 0;
  for (int y = int(hi.y()) + 3; y <= int(lo.y()) - 3; ++y) {
    for (int x = int(lo.x()) + 3; x <= int(hi.x()) - 3; ++x)
      gaps += is_background(r.image.at(x, y));
    const double here = grey(r.image.at(sx, y));
    const double around = 0.5 * (grey(r.image.at(sx - 2, y)) + grey(r.image.at(sx + 2, y)));
    worst = std::max(worst, std::abs(here - around));
  }
  EXPECT_EQ(gaps, 0);
  EXPECT_LT(worst, 3.0) << "a line shows at the seam";
}

int count_pixels(const render::Image& img, bool (*pred)(Rgb)) {
  int n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) n += pred(img.at(x, y));
  return n;
}

TEST(SurfacePicture, OverlaysDrawTheNetPointsAndRows) {
  const Rows rows = load_rows(example("ship_px121_stations.rows"));
  const FitResult f = fit_at(rows, 0.2);
  render::Scene sc;
  sc.surface = &f.surface;
  sc.rows = &rows;
  sc.row_v = f.v;
  auto red = [](Rgb c) { return c.r > 150 && c.g < 90 && c.b < 90; };
  auto dark = [](Rgb c) { return c.r < 60 && c.g < 60 && c.b < 60; };
  auto blue = [](Rgb c) { return c.b > 100 && c.r < 80 && c.g < 110; };
  render::RenderOptions o = small_options(Mode::kShaded);
  o.view = {135, 25, 2};
  const render::RenderResult plain = render::render_surface(sc, o);
  o.net = true;
  const render::RenderResult net = render::render_surface(sc, o);
  o.net = false;
  o.points = true;
  const render::RenderResult pts = render::render_surface(sc, o);
  o.points = false;
  o.rows = true;
  const render::RenderResult rws = render::render_surface(sc, o);
  EXPECT_EQ(count_pixels(plain.image, red), 0);
  EXPECT_GT(count_pixels(net.image, red), 300);
  // Each control point is drawn (in full, or faint where the surface hides it).
  int seen = 0;
  for (const Point& c : f.surface.control) {
    const Eigen::Vector3d q = net.camera.project(c);
    const Rgb a = net.image.at(int(q.x()), int(q.y())), b = plain.image.at(int(q.x()), int(q.y()));
    seen += a.r > a.g + 30 && !(a == b);
  }
  EXPECT_EQ(seen, static_cast<int>(f.surface.control.size()));
  EXPECT_EQ(count_pixels(plain.image, dark), 0);
  EXPECT_GT(count_pixels(pts.image, dark), 90);
  EXPECT_EQ(count_pixels(plain.image, blue), 0);
  EXPECT_GT(count_pixels(rws.image, blue), 400);
}

TEST(SurfacePicture, RejectsBadOptionsAndMissingData) {
  const Rows rows = load_rows(example("ship_px121_stations.rows"));
  const FitResult f = fit_at(rows, 0.2);
  render::Scene sc;
  sc.surface = &f.surface;
  auto code_and_option = [&](render::RenderOptions o) {
    try {
      render::render_surface(sc, o);
    } catch (const Error& e) {
      return std::pair(e.code(), e.place().option);
    }
    return std::pair(ErrorCode::kInternal, std::string("no error"));
  };
  render::RenderOptions o = small_options(Mode::kShaded);
  o.width = 10;
  EXPECT_EQ(code_and_option(o), std::pair(ErrorCode::kUsage, std::string("width")));
  o = small_options(Mode::kShaded);
  o.exaggeration = 0;
  EXPECT_EQ(code_and_option(o), std::pair(ErrorCode::kUsage, std::string("exaggeration")));
  o = small_options(Mode::kDeviation);
  EXPECT_EQ(code_and_option(o), std::pair(ErrorCode::kUsage, std::string("mode")));
  o = small_options(Mode::kShaded);
  o.points = true;
  EXPECT_EQ(code_and_option(o), std::pair(ErrorCode::kUsage, std::string("points")));
  EXPECT_THROW(render::parse_mode("wireframe", "--mode"), Error);
  EXPECT_THROW(render::parse_view("45", 2, "--view"), Error);
  EXPECT_THROW(render::parse_view("0,91", 2, "--view"), Error);
  EXPECT_EQ(render::parse_view("10,-20", 1, "--view").elevation, -20);
}

}  // namespace
}  // namespace sfit::test
