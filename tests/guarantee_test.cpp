// The guarantee: on every data set of examples/, at 1e-2, 1e-3 and 1e-4 of the
// bounding-box diagonal, with its closed flags, every data point is within T on every axis,
// checked twice: by Surface::evaluate and by the independent textbook evaluator on the
// JSON contract form.
#include <gtest/gtest.h>

#include "reference_eval.h"
#include "sfit/surface_fit.h"
#include "surface_json_value.h"
#include "test_support.h"

namespace sfit {
namespace {

struct DataSet {
  const char* file;
  bool closed_u;
};
const DataSet kSets[] = {
    {"d150_wing.rows", true},
    {"iea15mw_blade_af50.rows", true},
    {"iea3p4mw_blade_ragged9.rows", true},
    {"ship_px121_stations.rows", false},
    {"ring_body.rows", true},
    {"bent_tube.rows", true},
    {"spout_tube.rows", true},
    {"topobathy.rows", false},
    {"height_field.rows", false},
    {"height_field_small.rows", false},
    {"table1_synthetic.rows", false},
};

void PrintTo(const DataSet& d, std::ostream* os) {
  *os << d.file;
}

class Guarantee : public ::testing::TestWithParam<std::tuple<DataSet, double>> {};

TEST_P(Guarantee, EveryPointWithinTolerance) {
  const auto [set, fraction] = GetParam();
  const Rows rows = test::load_rows(test::example(set.file));
  FitOptions o;
  o.method = FitMethod::kSfit01;  // row_counts bound nu (the default's: control_points_test)
  o.closed_u = set.closed_u;
  o.tolerance = relative_tolerance(rows, fraction);
  const FitResult fit = fit_surface(rows, o);
  const FitReport& r = fit.report;
  EXPECT_TRUE(r.within_tolerance);
  EXPECT_EQ(r.points, rows.total_points());
  ASSERT_EQ(r.row_counts.size(), rows.size());
  EXPECT_EQ(r.count_u, fit.surface.count_u);
  EXPECT_GE(r.count_u, *std::max_element(r.row_counts.begin(), r.row_counts.end()));

  // Check 1: every point by Surface::evaluate (not the iso-curve path of check_deviation).
  Point worst = Point::Zero();
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (std::size_t k = 0; k < rows[j].size(); ++k) {
      const Point d = (fit.surface.evaluate(fit.u[rows.offsets()[j] + k],
                                            fit.point_v(j, rows.offsets()[j] + k)) -
                       rows[j][k])
                          .cwiseAbs();
      worst = worst.cwiseMax(d);
      ASSERT_TRUE((d.array() <= o.tolerance.array()).all())
          << "row " << j << " point " << k << " deviation " << d.transpose() << " T "
          << o.tolerance.x();
    }
  // The report measures in coordinates centred on the box, this loop in the raw ones: they
  // agree to round-off relative to the coordinates' magnitude.
  const BoundingBox box = bounding_box(rows);
  const double scale = box.min.cwiseAbs().cwiseMax(box.max.cwiseAbs()).maxCoeff() + box.diagonal();
  EXPECT_NEAR((worst - r.max_deviation).norm(), 0, 1e-13 * scale);

  // Check 2: the independent evaluator on the JSON form, at a sample of points and the worst.
  const auto ref = test::reference_from_json_text(io::surface_to_json(fit.surface).dump());
  const std::size_t stride = std::max<std::size_t>(1, rows.total_points() / 150);
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (std::size_t k = 0; k < rows[j].size(); ++k) {
      const bool is_worst =
          static_cast<long>(j) == r.worst_row && static_cast<long>(k) == r.worst_index;
      if ((rows.offsets()[j] + k) % stride != 0 && !is_worst) continue;
      const auto s =
          ref.evaluate(fit.u[rows.offsets()[j] + k], fit.point_v(j, rows.offsets()[j] + k));
      const Point d = (Point(s[0], s[1], s[2]) - rows[j][k]).cwiseAbs();
      EXPECT_TRUE((d.array() <= o.tolerance.array() * (1 + 1e-9)).all())
          << "reference evaluator: row " << j << " point " << k << " deviation " << d.transpose();
    }
}

std::string name_of(const ::testing::TestParamInfo<std::tuple<DataSet, double>>& info) {
  std::string n = std::get<0>(info.param).file;
  n = n.substr(0, n.find('.'));
  const double f = std::get<1>(info.param);
  return n + (f == 1e-2 ? "_1em2" : f == 1e-3 ? "_1em3" : "_1em4");
}

INSTANTIATE_TEST_SUITE_P(SharedData, Guarantee,
                         ::testing::Combine(::testing::ValuesIn(kSets),
                                            ::testing::Values(1e-2, 1e-3, 1e-4)),
                         name_of);

}  // namespace
}  // namespace sfit
