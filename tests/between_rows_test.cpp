// Whether a surface stays between its rows (between_rows.h) and near the data's box in the
// spans between spans with data (geometric_search.h's stays_near_where_covered()): the
// measure on calm and swinging surfaces, and the default on ship stations whose geometric
// surface once swung far out of the box between every two stations.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "between_rows.h"
#include "fit_driver.h"
#include "geometric_search.h"
#include "sfit/io/rows_reader.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

// 6 rows of 11 points on the plane z = 0 (x along a row, y = row), and a bicubic surface
// over [0, 10] x [0, 5] with 11 x 6 control points on the plane (uniform knots: each row lies
// on one knot line v = row, u = x), so the surface's parameters are the points' x and y.
Rows plane_rows() {
  Rows rows;
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i <= 10; ++i) rows.push_point(Point(i, j, 0));
    rows.end_row();
  }
  return rows;
}

// The plane rows' parameters on plane_surface(): u = x per point, v = the row's index.
std::pair<std::vector<double>, std::vector<double>> plane_parameters(const Rows& rows) {
  std::vector<double> u, v;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    v.push_back(static_cast<double>(j));
    for (const Point& p : rows[j]) u.push_back(p.x());
  }
  return {u, v};
}

Surface plane_surface(double swing) {
  Surface s;
  s.degree_u = s.degree_v = 3;
  s.count_u = 13;
  s.count_v = 8;
  for (int i = 0; i < s.count_u; ++i)
    for (int j = 0; j < s.count_v; ++j) {
      // Greville abscissae of the clamped uniform knots on [0, 10] and [0, 5].
      auto greville = [](int k, int n, double end) {
        const int spans = n - 3;
        double g = 0;
        for (int a = 1; a <= 3; ++a) g += std::clamp(k + a - 3, 0, spans);
        return g / 3 * end / spans;
      };
      // Control points alternating up and down across the rows: the surface passes near the
      // rows' points (z = 0 there, within a fraction of `swing`) and swings between them.
      s.control.push_back(Point(greville(i, s.count_u, 10), greville(j, s.count_v, 5),
                                swing * ((j % 2) ? 1.0 : -1.0)));
    }
  return s;
}

TEST(BetweenRows, ACalmSurfaceStaysBetweenItsRows) {
  const Rows rows = plane_rows();
  const Surface s = plane_surface(0.0);
  const auto [u, v] = plane_parameters(rows);
  const detail::RowPairs pairs = detail::row_pairs(rows, false);
  EXPECT_EQ(pairs.points.size(), 5u * 11u);  // every point of the first 5 rows
  EXPECT_LT(detail::between_rows_ratio(s, rows, pairs, u, v, 0.01), 1e-9);
}

TEST(BetweenRows, ASurfaceThatSwingsBetweenItsRowsIsMeasured) {
  const Rows rows = plane_rows();
  const Surface s = plane_surface(20.0);
  const auto [u, v] = plane_parameters(rows);
  const detail::RowPairs pairs = detail::row_pairs(rows, false);
  EXPECT_GT(detail::between_rows_ratio(s, rows, pairs, u, v, 0.01), detail::kBetweenRowsLimit);
}

// 24 stations of a hard-chine hull with a deck corner (tests/between_rows_data/). The
// geometric rule once took 9 x 119 control points for them: each station spread over a few of
// the 116 spans along v by the base plane's tilt, and the columns swung 15 m out of the box
// (0.2 of its diagonal) between every two stations to shape the stations. Now the default's
// surface holds T, stays within a tenth of the diagonal of the box, and runs calmly between
// the stations.
TEST(BetweenRows, ShipStationsGetNoSurfaceThatSwingsBetweenThem) {
  const Rows rows =
      io::read_rows(std::string(SFIT_TESTS_DIR) + "/between_rows_data/ship_stations_24.rows").rows;
  const FitOptions o = test::at(rows, 1e-3);
  const FitResult f = fit_surface(rows, o);
  EXPECT_TRUE(f.report.within_tolerance);
  const Point d = test::reference_deviation(f, rows);
  EXPECT_TRUE((d.array() <= o.tolerance.array() * (1 + 1e-9)).all()) << d.transpose();
  const double diagonal = bounding_box(rows).diagonal();
  EXPECT_LT(f.report.box_excursion, 0.1 * diagonal);
  EXPECT_EQ(f.report.fold, 0.0);
  const std::vector<double>& v = f.v_points.empty() ? f.v : f.v_points;
  EXPECT_LT(detail::between_rows_ratio(f.surface, rows, detail::row_pairs(rows, false), f.u, v,
                                       o.tolerance.maxCoeff()),
            1.0);
}

}  // namespace
}  // namespace sfit
