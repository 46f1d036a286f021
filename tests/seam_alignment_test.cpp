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

// Rings of equal point count rotated and reversed come back to the order the original rings
// are aligned to, exactly: whole shifts, the same seam point in every ring.
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
  const RowAlignment original = align_rows(equal, true, SeamMode::kAlign, OrientMode::kAuto);
  const Rows scrambled = test::rotated_copy(equal, 7, true);
  const RowAlignment a = align_rows(scrambled, true, SeamMode::kAlign, OrientMode::kAuto);
  EXPECT_EQ(apply_alignment(scrambled, a).points(), apply_alignment(equal, original).points());
  int reversed = 0;
  for (const RowSeam& s : a.rows) {
    reversed += s.reversed;
    EXPECT_EQ(s.offset, 0.0);
  }
  EXPECT_EQ(reversed, static_cast<int>(rows.size()) / 2);
  // The seams lie on the first ring's point farthest from its box's centre (of the two ends
  // of the ellipse's long axis, the one the next ring's points line up with as well).
  const std::size_t seam = source_index(original.rows[0], 40, 0);
  EXPECT_TRUE(seam == 10 || seam == 30) << seam;
  for (const RowSeam& s : original.rows) EXPECT_EQ(s.shift, original.rows[0].shift);
  // Keep + keep touches nothing; align + keep only shifts.
  EXPECT_TRUE(align_rows(scrambled, true, SeamMode::kKeep, OrientMode::kKeep).identity());
  for (const RowSeam& s : align_rows(scrambled, true, SeamMode::kAlign, OrientMode::kKeep).rows)
    EXPECT_FALSE(s.reversed);
}

// Rows that correspond and start at the seam alignment's own point keep their order: the wing
// (its trailing edge, the sharpest corner, starts every row), sections whose first points are
// where the symmetric section's farthest points tie (a torus-like tube of regular polygons),
// the ship's open stations; and rows aligned once are not moved again (the ragged rings keep
// their fractional seams).
TEST(SeamAlignment, CorrespondingRowsAreKept) {
  const Rows wing = test::load_rows(test::example("d150_wing.rows"));
  EXPECT_TRUE(align_rows(wing, true, SeamMode::kAlign, OrientMode::kAuto).identity());
  const Rows torus = test::sample_rows(
      [](double s, double t) {
        const double a = 2 * 3.14159265358979323846 * s, r = 0.5 + 0.1 * t;
        return Point(2 + r * std::cos(a), 3 * t, r * std::sin(a));
      },
      std::vector<int>(12, 20), true);
  EXPECT_TRUE(align_rows(torus, true, SeamMode::kAlign, OrientMode::kAuto).identity());
  for (const Rows& rows : {test::teapot_handle_like(), test::teapot_spout_like(),
                           test::fuselage_like(), test::teapot_body_like()}) {
    const RowAlignment once = align_rows(rows, true, SeamMode::kAlign, OrientMode::kAuto);
    const RowAlignment twice =
        align_rows(apply_alignment(rows, once), true, SeamMode::kAlign, OrientMode::kAuto);
    for (std::size_t j = 0; j < rows.size(); ++j) {
      // The seam where it was: once's offset past point 0 (half a spacing past one point is
      // half a spacing before the next).
      const double n = static_cast<double>(rows[j].size());
      double d =
          static_cast<double>(twice.rows[j].shift) + twice.rows[j].offset - once.rows[j].offset;
      d -= n * std::floor(d / n + 0.5);
      EXPECT_NEAR(d, 0.0, 1e-3) << j;
      EXPECT_FALSE(twice.rows[j].reversed) << j;
    }
  }
  const Rows ship = test::load_rows(test::example("ship_px121_stations.rows"));
  EXPECT_TRUE(align_rows(ship, false, SeamMode::kAlign, OrientMode::kAuto).identity());
}

struct ClosedSet {
  const char* name;
  Rows (*make)();
  double fraction = 1e-3;  // of the data's diagonal (the big blade's dense gap costs minutes)
};
Rows wing() {
  return test::load_rows(test::example("d150_wing.rows"));
}
Rows blade() {
  return test::load_rows(test::example("iea3p4mw_blade_ragged9.rows"));
}
Rows big_blade() {
  return test::load_rows(test::example("iea15mw_blade_af50.rows"));
}
Rows ring_body() {
  return test::load_rows(test::example("ring_body.rows"));
}
Rows bent_tube() {
  return test::load_rows(test::example("bent_tube.rows"));
}
Rows spout_tube() {
  return test::load_rows(test::example("spout_tube.rows"));
}
const ClosedSet kClosed[] = {{"d150_wing", wing},
                             {"iea3p4mw_blade_ragged9", blade},
                             {"iea15mw_blade_af50", big_blade, 1e-2},
                             {"ring_body", ring_body},
                             {"bent_tube", bent_tube},
                             {"spout_tube", spout_tube},
                             {"teapot_body_like", test::teapot_body_like},
                             {"teapot_handle_like", test::teapot_handle_like},
                             {"teapot_spout_like", test::teapot_spout_like},
                             {"fuselage_like", test::fuselage_like}};

class RotatedSections : public ::testing::TestWithParam<std::tuple<ClosedSet, bool>> {};

// The must-show: rotated (and every other reversed) copies fit to the same surface as the
// originals, within 5 T on dense samples between the rows, with at most 10 % more control
// points, by either method; with --seam keep the same copies give another surface.
void expect_same_surface_from_copies(const ClosedSet& set, bool reverse, FitMethod method) {
  const Rows rows = set.make();
  FitOptions o = closed_options(rows, set.fraction);
  o.method = method;
  const double T = o.tolerance.x();
  const FitResult original = fit_surface(rows, o);
  ASSERT_TRUE(original.report.within_tolerance);
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const Rows copy = test::rotated_copy(rows, seed, reverse);
    const FitResult f = fit_surface(copy, o);
    ASSERT_TRUE(f.report.within_tolerance);
    const double gap = test::surface_gap(original, f);
    EXPECT_LE(gap, 5 * T) << set.name << " seed " << seed << ": " << gap / T << " T";
    EXPECT_LE(control_points(f), 1.1 * control_points(original))
        << set.name << " seed " << seed << ": " << f.surface.count_u << " x " << f.surface.count_v
        << " against " << original.surface.count_u << " x " << original.surface.count_v;
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
      // As given, unless corner knots moved each row's start onto its seam corner.
      EXPECT_TRUE(k.report.seams.empty() || k.report.knots == KnotRule::kCorners);
      std::printf("%s%s, %s: aligned %.2f T (%ld control points, original %ld), as given %.1f T\n",
                  set.name, reverse ? " reversed" : "", std::string(to_string(method)).c_str(),
                  gap / T, control_points(f), control_points(original),
                  test::surface_gap(original, k) / T);
    }
  }
}

// The two-stage method at the paper's parameters.
TEST_P(RotatedSections, FitTheSameSurface) {
  const auto [set, reverse] = GetParam();
  expect_same_surface_from_copies(set, reverse, FitMethod::kSfit01);
}

// The default surface search (its positions measured from the fractional seams).
TEST_P(RotatedSections, DefaultSearchFitsTheSameSurface) {
  const auto [set, reverse] = GetParam();
  expect_same_surface_from_copies(set, reverse, FitOptions{}.method);
}

INSTANTIATE_TEST_SUITE_P(Sets, RotatedSections,
                         ::testing::Combine(::testing::ValuesIn(kClosed), ::testing::Bool()),
                         [](const auto& info) {
                           return std::string(std::get<0>(info.param).name) +
                                  (std::get<1>(info.param) ? "_reversed" : "");
                         });

// The IEA 15 MW blade at 1e-3 (50 sections of 199 and 200 points; its round root sections
// once drifted by 4 spacings against the trailing edges, and the copies needed 64 x 43 control
// points against 45 x 43): its copies get the original's counts by either method (the dense
// gap at this tolerance, 1.3 T and 0.9 T, is measured in docs/seams.md, not here: minutes).
TEST(RotatedSections, BigBladeCopiesKeepTheCountsAtFineTolerance) {
  const Rows rows = big_blade();
  for (FitMethod method : {FitMethod::kSfit01, FitOptions{}.method}) {
    FitOptions o = closed_options(rows, 1e-3);
    o.method = method;
    const FitResult original = fit_surface(rows, o);
    ASSERT_TRUE(original.report.within_tolerance);
    for (bool reverse : {false, true})
      for (std::uint32_t seed : {1u, 2u}) {
        const FitResult f = fit_surface(test::rotated_copy(rows, seed, reverse), o);
        EXPECT_TRUE(f.report.within_tolerance);
        EXPECT_LE(control_points(f), 1.1 * control_points(original))
            << to_string(method) << " seed " << seed << (reverse ? " reversed" : "") << ": "
            << f.surface.count_u << " x " << f.surface.count_v << " against "
            << original.surface.count_u << " x " << original.surface.count_v;
      }
  }
}

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
  // The row rules measure the gap between rows; the geometric rule's rows are no iso-curves.
  if (f.report.parametrization == Parametrization::kGeometric) {
    EXPECT_EQ(j.at("parameters_across"), "geometric");
  } else {
    EXPECT_GT(j.at("row_gap").get<double>(), 0.0);
    EXPECT_EQ(j.at("parameters_across"), "paper");
  }
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
