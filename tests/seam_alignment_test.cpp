// Seam alignment of closed rows and orientation of open rows (docs/seams.md): sections that
// start anywhere and run either way give the surface of sections that correspond.
#include "sfit/seam_alignment.h"

#include <gtest/gtest.h>

#include "deviation.h"
#include "sfit/io/surface_json.h"
#include "sfit/surface_fit.h"
#include "shapes.h"
#include "surface_distance.h"
#include "surface_json_value.h"
#include "test_support.h"

namespace sfit {
namespace {

FitOptions closed_options(const Rows& rows, double fraction = 1e-3) {
  FitOptions o;
  o.closed_u = true;
  o.tolerance = relative_tolerance(rows, fraction);
  return o;
}

long control_points(const FitResult& f) {
  return static_cast<long>(f.surface.count_u) * f.surface.count_v;
}

TEST(SeamAlignment, NamesRoundTrip) {
  SeamMode s;
  OrientMode o;
  ASSERT_TRUE(parse_seam_mode("keep", s));
  EXPECT_EQ(to_string(s), "keep");
  ASSERT_TRUE(parse_seam_mode("align", s));
  EXPECT_EQ(to_string(s), "align");
  ASSERT_TRUE(parse_orient_mode("keep", o));
  EXPECT_EQ(to_string(o), "keep");
  ASSERT_TRUE(parse_orient_mode("auto", o));
  EXPECT_EQ(to_string(o), "auto");
  EXPECT_FALSE(parse_seam_mode("Align", s));
  EXPECT_FALSE(parse_orient_mode("flip", o));
}

TEST(SeamAlignment, SourceIndexCoversEveryPointOnce) {
  for (const RowSeam s :
       {RowSeam{0, false}, RowSeam{3, false}, RowSeam{3, true}, RowSeam{6, true}}) {
    std::vector<int> seen(7, 0);
    for (std::size_t k = 0; k < 7; ++k) ++seen[source_index(s, 7, k)];
    for (int c : seen) EXPECT_EQ(c, 1);
  }
  EXPECT_EQ(source_index(RowSeam{3, false}, 7, 5), 1u);
  EXPECT_EQ(source_index(RowSeam{3, true}, 7, 5), 5u);
  EXPECT_EQ(source_index(RowSeam{6, true}, 7, 0), 6u);  // an open reversed row
}

// Rings of equal point count rotated and reversed come back to the first ring's order exactly.
TEST(SeamAlignment, RecoversShiftsAndDirections) {
  const Rows rows = test::fuselage_like();
  Rows equal;  // every ring with 40 points, so whole-index shifts are exact
  for (std::size_t j = 0; j < rows.size(); ++j) {
    std::vector<Point> p;
    for (int k = 0; k < 40; ++k) {
      const double th = 2 * 3.14159265358979323846 * k / 40;
      const double r = 1 + 0.1 * static_cast<double>(j);
      p.push_back(Point(static_cast<double>(j), r * std::cos(th), 1.2 * r * std::sin(th)));
    }
    equal.add_row(p);
  }
  Rows scrambled = test::rotated_copy(equal, 7, true);
  // Row 0 as given: the surface follows its start.
  std::vector<Point> first(equal[0].begin(), equal[0].end());
  Rows input;
  input.add_row(first);
  for (std::size_t j = 1; j < scrambled.size(); ++j) input.add_row(scrambled[j]);
  const RowAlignment a = align_rows(input, true, SeamMode::kAlign, OrientMode::kAuto);
  const Rows aligned = apply_alignment(input, a);
  EXPECT_EQ(aligned.points(), equal.points());
  int reversed = 0;
  for (const RowSeam& s : a.rows) reversed += s.reversed;
  EXPECT_EQ(reversed, static_cast<int>(rows.size()) / 2);
  // Keep + keep touches nothing; align + keep only shifts.
  EXPECT_TRUE(align_rows(input, true, SeamMode::kKeep, OrientMode::kKeep).identity());
  for (const RowSeam& s : align_rows(input, true, SeamMode::kAlign, OrientMode::kKeep).rows)
    EXPECT_FALSE(s.reversed);
}

// Rows that correspond keep their order (the blade does not: its sharpest trailing edge corner
// is one point past the start of its row, and every seam moves onto it).
TEST(SeamAlignment, CorrespondingRowsAreKept) {
  const Rows wing = test::load_rows(test::example("d150_wing.rows"));
  EXPECT_TRUE(align_rows(wing, true, SeamMode::kAlign, OrientMode::kAuto).identity());
  for (const Rows& rows :
       {test::teapot_handle_like(), test::teapot_spout_like(), test::fuselage_like()})
    EXPECT_TRUE(align_rows(rows, true, SeamMode::kAlign, OrientMode::kAuto).identity());
  const Rows ship = test::load_rows(test::example("ship_px121_stations.rows"));
  EXPECT_TRUE(align_rows(ship, false, SeamMode::kAlign, OrientMode::kAuto).identity());
}

struct ClosedSet {
  const char* name;
  Rows (*make)();
};
Rows wing() {
  return test::load_rows(test::example("d150_wing.rows"));
}
Rows blade() {
  return test::load_rows(test::example("iea3p4mw_blade_ragged9.rows"));
}
const ClosedSet kClosed[] = {{"d150_wing", wing},
                             {"iea3p4mw_blade_ragged9", blade},
                             {"teapot_body_like", test::teapot_body_like},
                             {"teapot_handle_like", test::teapot_handle_like},
                             {"teapot_spout_like", test::teapot_spout_like},
                             {"fuselage_like", test::fuselage_like}};

class RotatedSections : public ::testing::TestWithParam<std::tuple<ClosedSet, bool>> {};

// The must-show: rotated (and every other reversed) copies fit to the same surface as the
// originals, within 5 T on dense samples between the rows, with at most 10 % more control
// points; with --seam keep the same copies give another surface.
TEST_P(RotatedSections, FitTheSameSurface) {
  const auto [set, reverse] = GetParam();
  const Rows rows = set.make();
  // The two-stage method: its counts follow the aligned rows closely. The default surface
  // search can find far fewer control points on rows whose seams lie exactly on one meridian
  // than on rotated copies aligned to a fraction of a spacing (DefaultSearchOnRotatedCopies).
  FitOptions o = closed_options(rows);
  o.method = FitMethod::kSfit01;
  o.parametrization = Parametrization::kPaper;
  const double T = o.tolerance.x();
  const FitResult original = fit_surface(rows, o);
  ASSERT_TRUE(original.report.within_tolerance);
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const Rows copy = test::rotated_copy(rows, seed, reverse);
    const FitResult f = fit_surface(copy, o);
    ASSERT_TRUE(f.report.within_tolerance);
    ASSERT_EQ(f.report.seams.size(), rows.size());
    const double gap = test::surface_gap(original, f);
    EXPECT_LE(gap, 5 * T) << set.name << " seed " << seed << ": " << gap / T << " T";
    EXPECT_LE(control_points(f), 1.1 * control_points(original)) << set.name << " seed " << seed;
    // The check measured the original points of the copy at their u.
    const DeviationCheck c =
        check_deviation(f.surface, copy, f.u, f.v, o.tolerance, f.report.roundoff);
    EXPECT_TRUE(c.within);
    EXPECT_LE((c.max_deviation - f.report.max_deviation).norm(), 1e-9 * T);
    if (seed == 1) {
      FitOptions keep = o;
      keep.seam = SeamMode::kKeep;
      keep.orient = OrientMode::kKeep;
      const FitResult k = fit_surface(copy, keep);
      EXPECT_TRUE(k.report.seams.empty());
      std::printf("%s%s: aligned %.2f T (%ld control points, original %ld), as given %.1f T\n",
                  set.name, reverse ? " reversed" : "", gap / T, control_points(f),
                  control_points(original), test::surface_gap(original, k) / T);
    }
  }
}

// The default surface search on the same copies: every point within T, the surface within
// 5 T of the original's, and never more control points than the two stages on the copy.
TEST_P(RotatedSections, DefaultSearchOnRotatedCopies) {
  const auto [set, reverse] = GetParam();
  const Rows rows = set.make();
  const FitOptions o = closed_options(rows);
  const double T = o.tolerance.x();
  const FitResult original = fit_surface(rows, o);
  ASSERT_TRUE(original.report.within_tolerance);
  const Rows copy = test::rotated_copy(rows, 1u, reverse);
  const FitResult f = fit_surface(copy, o);
  ASSERT_TRUE(f.report.within_tolerance);
  EXPECT_LE(test::surface_gap(original, f), 5 * T) << set.name;
  FitOptions two = o;
  two.method = FitMethod::kSfit01;
  EXPECT_LE(control_points(f), control_points(fit_surface(copy, two))) << set.name;
  std::printf("%s%s: default on the copy %ld control points (original %ld)\n", set.name,
              reverse ? " reversed" : "", control_points(f), control_points(original));
}

INSTANTIATE_TEST_SUITE_P(Sets, RotatedSections,
                         ::testing::Combine(::testing::ValuesIn(kClosed), ::testing::Bool()),
                         [](const auto& info) {
                           return std::string(std::get<0>(info.param).name) +
                                  (std::get<1>(info.param) ? "_reversed" : "");
                         });

// Open rows: every other one reversed is found and flipped back: the same surface bit for bit.
TEST(RowOrientation, ReversedOpenRowsGiveTheSameSurface) {
  const Rows rows = test::load_rows(test::example("ship_px121_stations.rows"));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  const FitResult original = fit_surface(rows, o);
  const Rows flipped = test::every_other_reversed(rows);
  const FitResult f = fit_surface(flipped, o);
  EXPECT_EQ(f.surface.control, original.surface.control);
  ASSERT_EQ(f.report.seams.size(), rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    EXPECT_EQ(f.report.seams[j].reversed, j % 2 == 1) << j;
    // u of the reversed row's point k is the original's u of point N-1-k.
    const std::size_t n = rows[j].size(), o0 = rows.offsets()[j];
    for (std::size_t k = 0; k < n; ++k)
      EXPECT_EQ(f.u[o0 + k], original.u[o0 + (j % 2 ? n - 1 - k : k)]);
  }
  // The worst point is named in the input's order.
  const long wr = f.report.worst_row, wi = f.report.worst_index;
  ASSERT_GE(wr, 0);
  const long ow = original.report.worst_index;
  EXPECT_EQ(wr, original.report.worst_row);
  EXPECT_EQ(wi, wr % 2 ? static_cast<long>(rows[wr].size()) - 1 - ow : ow);
  // The JSON report lists the reversed rows and the shape measures.
  const auto j = io::report_to_json(f.report);
  ASSERT_EQ(j.at("seams").size(), rows.size() / 2);
  EXPECT_EQ(j.at("seams")[0][0], 1);
  EXPECT_EQ(j.at("seams")[0][2], true);
  EXPECT_EQ(j.at("fold"), f.report.fold);
  EXPECT_EQ(j.at("box_excursion"), f.report.box_excursion);
  EXPECT_GT(j.at("row_gap").get<double>(), 0.0);
  EXPECT_EQ(j.at("parameters_across"), "paper");
  // --orient keep fits them as given: another (worse) surface.
  FitOptions keep = o;
  keep.orient = OrientMode::kKeep;
  const FitResult k = fit_surface(flipped, keep);
  EXPECT_TRUE(k.report.seams.empty());
  EXPECT_GT(test::surface_gap(original, k), 5 * o.tolerance.x());
}

// Already corresponding rows: the default is the paper's scheme bit for bit.
TEST(SeamAlignment, DefaultEqualsKeepOnCorrespondingRows) {
  for (const char* name : {"d150_wing.rows"}) {
    const Rows rows = test::load_rows(test::example(name));
    FitOptions o = closed_options(rows);
    const FitResult a = fit_surface(rows, o);
    o.seam = SeamMode::kKeep;
    o.orient = OrientMode::kKeep;
    test::expect_same_surface(a, fit_surface(rows, o));
    EXPECT_TRUE(a.report.seams.empty());
  }
}

}  // namespace
}  // namespace sfit
