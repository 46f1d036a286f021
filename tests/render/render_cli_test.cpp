// sfit render, sfit render-rows and sfit fit --png, end to end: the pictures they write and
// their errors.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "picture_checks.h"
#include "sfit/render/image.h"
#include "surface_json_value.h"
#include "test_support.h"

namespace sfit::test {
namespace {

const std::string kHull = example("ship_px121_stations.rows");

// The report's max |d|/T of a surface file sfit wrote.
double report_ratio(const std::string& json_path) {
  const auto j = nlohmann::json::parse(read_file(json_path));
  double m = 0;
  for (int a = 0; a < 3; ++a)
    m = std::max(m, j["report"]["max_deviation"][a].get<double>() /
                        j["report"]["tolerance"][a].get<double>());
  return m;
}

TEST(RenderCli, FitPngDrawsTheReportsDeviations) {
  const std::string dir = temp_dir();
  const test::Run r = run_cli("fit '" + kHull + "' --tol 0.2 -o '" + dir + "/h.json' --png '" +
                              dir + "/d.png' --mode deviation --size 400x300 --view 135,25");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The CLI names the worst point's pixel; its colour there is the report's ratio.
  const auto at = r.err.find("deviation picture: max |d|/T ");
  ASSERT_NE(at, std::string::npos) << r.err;
  double ratio = 0;
  long point = 0;
  int px = 0, py = 0;
  ASSERT_EQ(
      std::sscanf(r.err.c_str() + at,
                  "deviation picture: max |d|/T %lf at point %ld of the input, pixel (%d, %d)",
                  &ratio, &point, &px, &py),
      4)
      << r.err;
  const double want = report_ratio(dir + "/h.json");
  EXPECT_NEAR(ratio, want, 1e-3);
  const render::Image img = render::read_png(dir + "/d.png");
  EXPECT_EQ(img.width, 400);
  EXPECT_EQ(img.height, 300);
  double dist = 0;
  const double t = decode_sequential(img.at(px, py), &dist);
  EXPECT_LT(dist, 4.0);
  EXPECT_NEAR(t, want, 0.02);
}

TEST(RenderCli, FitWritesOnePicturePerPngWithItsMode) {
  const std::string dir = temp_dir();
  const test::Run r = run_cli("fit '" + kHull + "' --png '" + dir + "/a.png' --png '" + dir +
                              "/b.png' --mode shaded --mode zebra --size 320x240 --view 135,25 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const render::Image a = render::read_png(dir + "/a.png"), b = render::read_png(dir + "/b.png");
  EXPECT_EQ(a.width, 320);
  // Zebra is black and white; shaded is not (only its title is dark).
  auto dark = [](const render::Image& img) {
    int n = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) n += img.at(x, y).g < 40;
    return n;
  };
  EXPECT_GT(dark(b), dark(a) + 1500);
}

TEST(RenderCli, RenderSurfaceFileWithClosestPointDeviations) {
  const std::string dir = temp_dir();
  ASSERT_EQ(run_cli("fit '" + kHull + "' --tol 0.2 -q -o '" + dir + "/h.json'").exit_code, 0);
  const test::Run r = run_cli("render '" + dir + "/h.json' --data '" + kHull +
                              "' --mode deviation --points --size 320x240 -o '" + dir + "/d.png'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto at = r.err.find("closest-point deviation: max |d|/T ");
  ASSERT_NE(at, std::string::npos) << r.err;
  double closest = 0;
  ASSERT_EQ(std::sscanf(r.err.c_str() + at, "closest-point deviation: max |d|/T %lf", &closest), 1);
  // The closest point is never farther than the fitted parameter's point. Per axis that orders
  // the ratios where the fitted deviation is normal to the surface, as the row rules' nearly
  // are; the geometric rule's parameters are projections onto a base plane, whose deviation
  // may lean (0.71 T on two axes, say, where the closest point's is 0.8 T on one): there the
  // closest point holds T.
  const auto h = nlohmann::json::parse(read_file(dir + "/h.json"));
  if (h["report"]["parameters"] == "geometric") {
    EXPECT_LE(closest, 1.0 + 1e-3);
  } else {
    EXPECT_LE(closest, report_ratio(dir + "/h.json") + 1e-3);
  }
  EXPECT_NE(r.err.find("the report (at the fitted parameters)"), std::string::npos);
  EXPECT_EQ(render::read_png(dir + "/d.png").width, 320);
  for (const char* mode : {"shaded", "zebra", "gauss", "mean"}) {
    const test::Run k =
        run_cli("render '" + dir + "/h.json' --mode " + mode +
                " --net --view top --size 160x120 -q -o '" + dir + "/" + mode + ".png'");
    EXPECT_EQ(k.exit_code, 0) << mode << ": " << k.err;
    EXPECT_EQ(render::read_png(dir + "/" + mode + ".png").height, 120) << mode;
  }
}

TEST(RenderCli, RenderRowsDrawsOneRow) {
  const std::string dir = temp_dir();
  const test::Run r = run_cli("render-rows '" + example("iea3p4mw_blade_ragged9.rows") +
                              "' --row 3 --closed u --size 480x360 -o '" + dir + "/r.png'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("row 3: 76 points"), std::string::npos) << r.err;
  EXPECT_EQ(render::read_png(dir + "/r.png").width, 480);
}

TEST(RenderCli, ErrorsNameTheOptionAndWriteNothing) {
  const std::string dir = temp_dir();
  ASSERT_EQ(run_cli("fit '" + kHull + "' -q -o '" + dir + "/h.json'").exit_code, 0);
  const std::string h = "'" + dir + "/h.json'", out = " -o '" + dir + "/x.png'";
  struct Case {
    std::string args;
    int code;
    std::string says;
  };
  const Case cases[] = {
      {"render " + h + " --mode wireframe" + out, 2, "--mode"},
      {"render " + h + " --view 45" + out, 2, "--view"},
      {"render " + h + " --size 10x10" + out, 2, "--size"},
      {"render " + h + " --up w" + out, 2, "--up"},
      {"render " + h + " --exaggerate 0" + out, 2, "--exaggerate"},
      {"render " + h + " --points" + out, 2, "--data"},
      {"render " + h + " --mode deviation" + out, 2, "--data"},
      {"render " + h + " -o '" + dir + "/x.jpg'", 2, "-o"},
      {"render " + h, 2, "-o"},
      {"render '" + dir + "/missing.json'" + out, 3, "missing.json"},
      {"render " + h + " -o '" + dir + "/no/such/x.png'", 6, "x.png"},
      {"render-rows '" + kHull + "' --row 11" + out, 2, "--row"},
      {"render-rows '" + kHull + "' --row 2 --closed w" + out, 2, "--closed"},
      {"fit '" + kHull + "' --png '" + dir + "/x.png' --mode a --mode b --mode c", 2, "--mode"},
      {"fit '" + kHull + "' --mode zebra -o '" + dir + "/y.json'", 2, "--png"},
  };
  for (const Case& c : cases) {
    const test::Run r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, c.code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/y.json"));
  // A picture that cannot be written is refused before the fit: no surface file either.
  const test::Run r =
      run_cli("fit '" + kHull + "' -o '" + dir + "/z.json' --png '" + dir + "/no/such/z.png'");
  EXPECT_EQ(r.exit_code, 6) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/z.json"));
}

TEST(RenderCli, ClosedRingBodyHasNoGapAtItsSeam) {
  const std::string teapot = example("ring_body.rows");
  const std::string dir = temp_dir();
  // Seen from above: the body's rim ring (closed rows) must be drawn all round, the seam too.
  const test::Run r = run_cli("fit '" + teapot + "' --closed u -q --png '" + dir +
                              "/t.png' --view top --size 320x320");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const render::Image img = render::read_png(dir + "/t.png");
  // From above the body is a ring (the open bottom shows through its middle). Every row and
  // column below the title crosses it in at most two runs, the middle ones in exactly two: a
  // crack along the seam (a radius) would cut a run in two or leave a row empty.
  auto runs = [&](int x0, int y0, int dx, int dy) {
    int n = 0;
    bool in = false;
    for (int x = x0, y = y0; img.contains(x, y); x += dx, y += dy) {
      const bool drawn = !is_background(img.at(x, y));
      n += drawn && !in;
      in = drawn;
    }
    return n;
  };
  const int top = 40;  // below the two title lines
  int most = 0;
  for (int y = top; y < img.height; ++y) most = std::max(most, runs(0, y, 1, 0));
  for (int x = 0; x < img.width; ++x) most = std::max(most, runs(x, top, 0, 1));
  EXPECT_EQ(most, 2);
  const int cy = (top + img.height) / 2;
  for (int dy = -20; dy <= 20; ++dy) EXPECT_EQ(runs(0, cy + dy, 1, 0), 2) << "row " << cy + dy;
  for (int dx = -20; dx <= 20; ++dx)
    EXPECT_EQ(runs(img.width / 2 + dx, top, 0, 1), 2) << "column " << img.width / 2 + dx;
}

}  // namespace
}  // namespace sfit::test
