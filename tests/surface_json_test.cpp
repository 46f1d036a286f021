#include "surface_json_value.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "sfit/error.h"
#include "test_support.h"

namespace sfit::io {
namespace {

Surface sample_surface(bool pu, bool pv) {
  Surface s;
  s.degree_u = 3;
  s.degree_v = 2;
  s.periodic_u = pu;
  s.periodic_v = pv;
  s.count_u = 6;
  s.count_v = 5;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 5; ++j)
      s.control.emplace_back(i + 0.1 / 3, j * 1e-17 + 1.0 / 7, std::sqrt(i * j + 2.0));
  return s;
}

TEST(SurfaceJson, FollowsTheContract) {
  const Surface s = sample_surface(true, false);
  const auto j = surface_to_json(s);
  EXPECT_EQ(j["type"], "bspline_surface");
  EXPECT_EQ(j["degree"], nlohmann::json({3, 2}));
  EXPECT_EQ(j["periodic"], nlohmann::json({true, false}));
  // Periodic u stored in full: 6 + 3 control points, knots 6 + 2*3 + 1 long.
  ASSERT_EQ(j["control_points"].size(), 9u);
  ASSERT_EQ(j["control_points"][0].size(), 5u);
  EXPECT_EQ(j["knots_u"].size(), 9u + 3 + 1);
  EXPECT_EQ(j["knots_v"].size(), 5u + 2 + 1);
  EXPECT_EQ(j["control_points"][6][2], j["control_points"][0][2]);  // wrap copy
}

TEST(SurfaceJson, ReloadsBitForBit) {
  for (bool pu : {false, true})
    for (bool pv : {false, true}) {
      const Surface s = sample_surface(pu, pv);
      const std::string path = test::temp_dir() + "/s.json";
      write_surface_json(path, s);
      const Surface r = read_surface_json(path);
      EXPECT_EQ(r.degree_u, s.degree_u);
      EXPECT_EQ(r.periodic_u, pu);
      EXPECT_EQ(r.periodic_v, pv);
      ASSERT_EQ(r.control.size(), s.control.size());
      EXPECT_EQ(0,
                std::memcmp(r.control.data(), s.control.data(), s.control.size() * sizeof(Point)));
    }
}

// The text is written a row of control points at a time: the same bytes as the whole JSON
// tree's dump, with and without the report, and the file holds exactly that text.
TEST(SurfaceJson, StreamedTextIsTheTreesDump) {
  FitReport r;
  r.points = 10;
  r.rows = 2;
  r.row_counts = {4, 5};
  r.stop_reason = "minimal \"quoted\" and \u00e9";
  r.max_deviation = Point(1e-300, 0.1, 12345.678);
  for (bool pu : {false, true})
    for (bool pv : {false, true})
      for (const FitReport* report : std::initializer_list<const FitReport*>{nullptr, &r}) {
        const Surface s = sample_surface(pu, pv);
        auto j = surface_to_json(s);
        if (report) j["report"] = report_to_json(*report);
        const std::string text = surface_json_text(s, report);
        EXPECT_EQ(text, j.dump() + '\n');
        const std::string path = test::temp_dir() + "/streamed.json";
        write_surface_json(path, s, report);
        std::ifstream in(path, std::ios::binary);
        const std::string file((std::istreambuf_iterator<char>(in)), {});
        EXPECT_EQ(file, text);
      }
}

TEST(SurfaceJson, ReportHasTheContractKeys) {
  FitReport r;
  r.points = 10;
  r.rows = 2;
  r.row_counts = {4, 5};
  const auto j = report_to_json(r);
  for (const char* key : {"points", "rows", "tolerance", "max_deviation", "worst",
                          "within_tolerance", "control_points", "row_counts", "seconds"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_TRUE(j["worst"].contains("deviation"));
}

TEST(SurfaceJson, RejectsBrokenSurfaces) {
  auto j = surface_to_json(sample_surface(false, false));
  j["knots_u"].erase(0);
  EXPECT_THROW(surface_from_json(j, "x.json"), Error);
  auto k = surface_to_json(sample_surface(true, false));
  k["control_points"][7][1][0] = 99.0;  // a wrap copy that differs
  EXPECT_THROW(surface_from_json(k, "x.json"), Error);
  const std::string path = test::temp_dir() + "/bad.json";
  test::write_file(path, "{ not json");
  try {
    read_surface_json(path);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputSyntax);
  }
}

}  // namespace
}  // namespace sfit::io
