// Per-point weights (docs/seams.md): weighted least squares in the curve stage, the 4th
// number in every rows format, clear errors for bad weights.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "basis.h"
#include "parameters.h"
#include "sfit/curve_fit.h"
#include "sfit/error.h"
#include "sfit/incremental.h"
#include "sfit/io/csv_reader.h"
#include "sfit/io/rows_binary.h"
#include "sfit/io/rows_reader.h"
#include "sfit/parametrization.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

std::vector<Point> noisy_row(int n) {
  std::vector<Point> p;
  for (int k = 0; k < n; ++k) {
    const double s = static_cast<double>(k) / (n - 1);
    p.push_back(Point(s, std::sin(3 * s) + 0.02 * std::sin(97.0 * k), 0.01 * std::cos(41.0 * k)));
  }
  return p;
}

// The dense reference: min sum w_j |B x - D_j|^2 by Householder QR on sqrt(w)-scaled rows.
std::vector<Point> dense_weighted_lsq(const std::vector<Point>& d, const std::vector<double>& w,
                                      int degree, int count, bool periodic) {
  const int n = static_cast<int>(d.size());
  const auto t = paper_parameters(degree, count, periodic, n);
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, count), D(n, 3);
  std::vector<double> b(static_cast<std::size_t>(degree) + 1);
  for (int j = 0; j < n; ++j) {
    const int f = eval_basis(degree, count, periodic, t[j], b.data());
    const double s = std::sqrt(w[j]);
    for (int a = 0; a <= degree; ++a) B(j, wrap_index(f + a, count)) += s * b[a];
    D.row(j) = s * d[j].transpose();
  }
  const Eigen::MatrixXd X = B.householderQr().solve(D);
  std::vector<Point> out(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) out[i] = X.row(i).transpose();
  return out;
}

TEST(Weights, WeightedFitEqualsDenseWeightedLeastSquares) {
  for (bool periodic : {false, true}) {
    const std::vector<Point> d = noisy_row(60);
    std::vector<double> w(d.size());
    for (std::size_t k = 0; k < w.size(); ++k) w[k] = 0.1 + static_cast<double>((k * 7) % 11);
    const CurveFit f = fit_curve_with_count(d, 3, periodic, 12, {}, w);
    const auto ref = dense_weighted_lsq(d, w, 3, 12, periodic);
    ASSERT_EQ(f.curve.count(), 12);
    for (int i = 0; i < 12; ++i) EXPECT_LT((f.curve.control[i] - ref[i]).norm(), 1e-12) << i;
    // And it is not the unweighted fit.
    const CurveFit u = fit_curve_with_count(d, 3, periodic, 12);
    EXPECT_GT((u.curve.control[5] - f.curve.control[5]).norm(), 1e-6);
  }
}

TEST(Weights, AHeavyPointIsHeldCloserThanItsNeighbours) {
  const std::vector<Point> d = noisy_row(80);
  std::vector<double> w(d.size(), 1.0);
  const std::size_t heavy = 40;
  w[heavy] = 1000;
  const CurveFit u = fit_curve_with_count(d, 3, false, 10);
  const CurveFit f = fit_curve_with_count(d, 3, false, 10, {}, w);
  auto dev = [&](const CurveFit& c, std::size_t k) {
    return (c.curve.evaluate(c.parameters[k]) - d[k]).norm();
  };
  EXPECT_LT(dev(f, heavy), 0.1 * dev(u, heavy));
  EXPECT_LT(dev(f, heavy), dev(f, heavy - 1));
  EXPECT_LT(dev(f, heavy), dev(f, heavy + 1));

  // In a surface fit: within T everywhere, and the heavy point closer than unweighted.
  Rows rows;
  for (int j = 0; j < 6; ++j) {
    std::vector<Point> r = d;
    for (Point& p : r) p.z() += 0.3 * j;
    rows.add_row(r);
  }
  FitOptions o;
  o.tolerance = Point::Constant(0.03);
  const FitResult plain = fit_surface(rows, o);
  std::vector<double> weights(rows.total_points(), 1.0);
  const std::size_t at = rows.offsets()[2] + heavy;
  weights[at] = 1000;
  rows.set_weights(weights);
  const FitResult weighted = fit_surface(rows, o);
  ASSERT_TRUE(weighted.report.within_tolerance);
  auto surf_dev = [&](const FitResult& r) {
    return (r.surface.evaluate(r.u[at], r.point_v(2, at)) - rows.points()[at]).norm();
  };
  EXPECT_LT(surf_dev(weighted), surf_dev(plain));
}

TEST(Weights, UnitWeightsGiveTheUnweightedFitBitForBit) {
  const Rows rows = test::load_rows(test::example("ship_px121_stations.rows"));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  Rows ones = rows;
  ones.set_weights(std::vector<double>(rows.total_points(), 1.0));
  test::expect_same_surface(fit_surface(rows, o), fit_surface(ones, o));
}

TEST(Weights, BadWeightsInTheApiNameTheRowAndPoint) {
  Rows rows = test::load_rows(test::example("ship_px121_stations.rows"));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  for (double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    std::vector<double> w(rows.total_points(), 1.0);
    w[rows.offsets()[3] + 2] = bad;
    rows.set_weights(w);
    try {
      fit_surface(rows, o);
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kInputData);
      EXPECT_EQ(e.place().row, 3);
      EXPECT_EQ(e.place().point, 2);
    }
  }
  rows.set_weights({1.0, 2.0});
  EXPECT_THROW(fit_surface(rows, o), Error);
}

void expect_error(const std::function<void()>& read, ErrorCode code, long line) {
  try {
    read();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_EQ(e.place().line, line) << e.what();
    EXPECT_FALSE(e.place().file.empty());
  }
}

TEST(Weights, FourthNumberOfRowsFiles) {
  const auto f = io::parse_rows("0 0 0 1\n1 0 0 2.5\n\n0 1 0 3\n1 1 0 4 # w\n", "w.rows");
  EXPECT_EQ(f.rows.weights(), (std::vector<double>{1, 2.5, 3, 4}));
  EXPECT_FALSE(io::parse_rows("0 0 0\n1 0 0\n", "p.rows").rows.weighted());
  for (const char* bad : {"0 0 0 1\n1 0 0 0\n", "0 0 0 1\n1 0 0 -2\n", "0 0 0 1\n1 0 0 nan\n"})
    expect_error([&] { io::parse_rows(bad, "bad.rows"); }, ErrorCode::kInputData, 2);
  expect_error([&] { io::parse_rows("0 0 0 1\n\n1 0 0\n", "mixed.rows"); }, ErrorCode::kInputSyntax,
               3);
  expect_error([&] { io::parse_rows("0 0 0\n1 0 0 1\n", "mixed.rows"); }, ErrorCode::kInputSyntax,
               2);
  expect_error([&] { io::parse_rows("0 0 0 1 5\n", "five.rows"); }, ErrorCode::kInputSyntax, 1);
}

TEST(Weights, WeightColumnOfCsvFiles) {
  EXPECT_EQ(io::parse_csv("0,0,0,1\n1,0,0,2\n", "w.csv").rows.weights(),
            (std::vector<double>{1, 2}));
  EXPECT_EQ(
      io::parse_csv("row,x,y,z,weight\n0,0,0,0,3\n0,1,0,0,4\n1,0,1,0,5\n", "w.csv").rows.weights(),
      (std::vector<double>{3, 4, 5}));
  EXPECT_FALSE(io::parse_csv("x,y,z\n0,0,0\n", "p.csv").rows.weighted());
  expect_error([&] { io::parse_csv("0,0,0,1\n1,0,0,0\n", "bad.csv"); }, ErrorCode::kInputData, 2);
  expect_error([&] { io::parse_csv("x,y,z,w\n0,0,0,1\n1,0,0,-1\n", "bad.csv"); },
               ErrorCode::kInputData, 3);
  expect_error([&] { io::parse_csv("0,0,0,1\n1,0,0\n", "mixed.csv"); }, ErrorCode::kInputSyntax, 2);
}

TEST(Weights, WeightsOfBinaryRowsRoundTrip) {
  Rows rows = test::load_rows(test::example("ship_px121_stations.rows"));
  std::vector<double> w(rows.total_points());
  for (std::size_t k = 0; k < w.size(); ++k) w[k] = 1 + 0.5 * static_cast<double>(k % 3);
  rows.set_weights(w);
  const std::string path = test::temp_dir() + "/w.srows";
  io::write_rows_binary(path, rows);
  const auto back = io::read_rows_binary(path);
  EXPECT_EQ(back.rows.points(), rows.points());
  EXPECT_EQ(back.rows.weights(), w);
  // A zero weight names row and point.
  w[rows.offsets()[2] + 1] = 0;
  rows.set_weights(w);
  io::write_rows_binary(path, rows);
  try {
    io::read_rows_binary(path);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputData);
    EXPECT_EQ(e.place().row, 2);
    EXPECT_EQ(e.place().point, 1);
  }
}

TEST(Weights, IncrementalEditsOfWeightedRowsAreRefused) {
  Rows rows = test::load_rows(test::example("ship_px121_stations.rows"));
  rows.set_weights(std::vector<double>(rows.total_points(), 2.0));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  IncrementalFit inc(rows, o);
  EXPECT_TRUE(inc.result().report.within_tolerance);
  try {
    inc.move_point(2, 1, rows[2][1] + Point(0, 0.01, 0));
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kUsage);
  }
}

TEST(Weights, CliReadsTheFourthColumn) {
  const std::string dir = test::temp_dir();
  test::write_file(dir + "/w.rows", "0 0 0 1\n1 0 0 1\n2 0 0.1 1\n\n0 1 0 1\n1 1 0.2 9\n2 1 0 1\n");
  const auto ok = test::run_cli("fit " + dir + "/w.rows -o " + dir + "/w.json");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  test::write_file(dir + "/bad.rows", "0 0 0 1\n1 0 0 1\n2 0 0.1 1\n\n0 1 0 1\n1 1 0.2 0\n");
  const auto bad = test::run_cli("fit " + dir + "/bad.rows -o " + dir + "/b.json");
  EXPECT_EQ(bad.exit_code, exit_code(ErrorCode::kInputData));
  EXPECT_NE(bad.err.find("bad.rows:6"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace sfit
