// The row picture: points, the curve-stage fit and its tolerance band in projections, and the
// per-axis deviations.
#include "sfit/render/row_picture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "picture_checks.h"
#include "sfit/curve_fit.h"
#include "sfit/error.h"

namespace sfit::test {
namespace {

using render::Rgb;

std::vector<Point> wavy_row(int n) {
  std::vector<Point> p;
  for (int k = 0; k < n; ++k) {
    const double x = double(k) / (n - 1);
    p.emplace_back(x, 0.3 * x, 0.05 * std::sin(2 * std::numbers::pi * x));
  }
  return p;
}

bool is_band(Rgb c) {
  return c.r > 240 && c.g > 195 && c.g < 230 && c.b > 130 && c.b < 175;
}

TEST(RowPicture, BandIsTheCurveSweptByTheBoundBox) {
  const auto pts = wavy_row(21);
  const Point bound = Point::Constant(0.1);
  const CurveFit fit = fit_curve(pts, {3, false, bound, CountSearch::kFast});
  render::RowPictureOptions o;
  o.width = 640;
  o.height = 480;
  o.supersample = 2;
  const render::RowPicture pic = render::render_row(pts, fit, bound, o);
  dump(pic.image, "row_band");
  const render::RowPanel& front = pic.panels[1];  // x across, z up
  ASSERT_EQ(front.axis_a, 0);
  ASSERT_EQ(front.axis_b, 2);
  // Down a column, the band reaches from the lowest to the highest point of the boxes
  // [c_x +- b_x] x [c_z +- b_z] of the curve points c over it.
  std::vector<Point> dense;
  for (int i = 0; i <= 4000; ++i)
    dense.push_back(fit.curve.evaluate(fit.curve.domain_end() * i / 4000));
  int checked = 0;
  for (double x : {0.125, 0.325, 0.525, 0.725}) {
    double lo = INFINITY, hi = -INFINITY;
    for (const Point& c : dense)
      if (std::abs(c.x() - x) <= bound.x()) {
        lo = std::min(lo, c.z() - bound.z());
        hi = std::max(hi, c.z() + bound.z());
      }
    const int px = static_cast<int>(std::floor(front.origin_x + front.scale * x));
    int first = -1, last = -1;
    for (int y = front.y0; y < front.y1; ++y)
      if (is_band(pic.image.at(px, y))) {
        if (first < 0) first = y;
        last = y;
      }
    ASSERT_GE(first, 0) << "no band at x = " << x;
    EXPECT_NEAR(first, front.origin_y - front.scale * hi, 2.0) << "top edge at x = " << x;
    EXPECT_NEAR(last, front.origin_y - front.scale * lo, 2.0) << "bottom edge at x = " << x;
    ++checked;
  }
  EXPECT_EQ(checked, 4);
  // Every point is drawn (dark) where its projection falls.
  for (const Point& p : pts) {
    const Rgb c = pic.image.at(static_cast<int>(front.origin_x + front.scale * p.x()),
                               static_cast<int>(front.origin_y - front.scale * p.z()));
    EXPECT_LT(c.r + c.g + c.b, 3 * 90) << p.transpose();
  }
}

TEST(RowPicture, WorstPointAndDeviationPlot) {
  const auto pts = wavy_row(31);
  const Point bound = Point::Constant(0.004);
  const CurveFit fit = fit_curve(pts, {3, false, bound, CountSearch::kFast});
  double want = 0;
  long want_j = -1;
  for (std::size_t j = 0; j < pts.size(); ++j) {
    const double r =
        ((fit.curve.evaluate(fit.parameters[j]) - pts[j]).cwiseAbs().cwiseQuotient(bound))
            .maxCoeff();
    if (r > want) want = r, want_j = static_cast<long>(j);
  }
  render::RowPictureOptions o;
  o.width = 640;
  o.height = 480;
  o.supersample = 2;
  const render::RowPicture pic = render::render_row(pts, fit, bound, o);
  EXPECT_NEAR(pic.worst_ratio, want, 1e-12);
  EXPECT_EQ(pic.worst_index, want_j);
  EXPECT_LE(pic.worst_ratio, 1.0);
  // The plot's +-1 lines (orange) are two rows, symmetric about the plot's middle.
  std::vector<int> orange_rows;
  for (int y = pic.plot_y0; y < pic.plot_y1; ++y) {
    int n = 0;
    for (int x = pic.plot_x0; x < pic.plot_x1; ++x) {
      const Rgb c = pic.image.at(x, y);
      n += c.r > 220 && c.g > 120 && c.g < 170 && c.b < 60;
    }
    if (n > (pic.plot_x1 - pic.plot_x0) / 2) orange_rows.push_back(y);
  }
  ASSERT_GE(orange_rows.size(), 2u);
  const double top = orange_rows.front(), bottom = orange_rows.back();
  EXPECT_GT(bottom - top, (pic.plot_y1 - pic.plot_y0) / 2.0);
}

TEST(RowPicture, ClosedRowAndRejectedSizes) {
  std::vector<Point> ring;
  for (int k = 0; k < 24; ++k) {
    const double a = 2 * std::numbers::pi * k / 24;
    ring.emplace_back(std::cos(a), 0.5 * std::sin(a), 0.2);
  }
  const Point bound = Point::Constant(0.05);  // a band wide enough to need no inset
  const CurveFit fit = fit_curve(ring, {3, true, bound, CountSearch::kFast});
  render::RowPictureOptions o;
  o.width = 400;
  o.height = 300;
  o.supersample = 1;
  const render::RowPicture pic = render::render_row(ring, fit, bound, o);
  dump(pic.image, "row_ring");
  EXPECT_EQ(pic.image.width, 400);
  // The top view shows the closed ring: its centre is empty, its outline drawn all round.
  const render::RowPanel& top = pic.panels[0];
  EXPECT_TRUE(is_background(pic.image.at(int(top.origin_x), int(top.origin_y))));
  for (int k = 0; k < 48; ++k) {
    const Point c = fit.curve.evaluate(fit.curve.domain_end() * k / 48);
    const Rgb px = pic.image.at(int(std::lround(top.origin_x + top.scale * c.x())),
                                int(std::lround(top.origin_y - top.scale * c.y())));
    EXPECT_FALSE(is_background(px)) << k;
  }
  o.width = 100;
  EXPECT_THROW(render::render_row(ring, fit, bound, o), Error);
}

}  // namespace
}  // namespace sfit::test
