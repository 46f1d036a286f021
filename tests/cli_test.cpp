// The sfit executable end to end: the main job, its outputs, and its exit codes.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "reference_eval.h"
#include "test_support.h"

namespace sfit {
namespace {

using test::run_cli;

TEST(Cli, FitWritesContractJsonAndReport) {
  const std::string dir = test::temp_dir();
  const auto r = run_cli("fit '" + test::example("ship_px121_stations.rows") + "' -o '" + dir +
                         "/hull.json' --report '" + dir + "/rep.json' --tol 0.05");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("every point within tolerance: yes"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(test::read_file(dir + "/hull.json"));
  EXPECT_EQ(j["type"], "bspline_surface");
  EXPECT_TRUE(j["report"]["within_tolerance"].get<bool>());
  const auto rep = nlohmann::json::parse(test::read_file(dir + "/rep.json"));
  EXPECT_EQ(rep["points"], 90);
  EXPECT_EQ(rep["rows"], 11);
  EXPECT_EQ(rep["tolerance"], nlohmann::json({0.05, 0.05, 0.05}));
  for (int a = 0; a < 3; ++a) EXPECT_LE(rep["max_deviation"][a].get<double>(), 0.05);
  // The surface interpolates nothing in particular, but its corner is near the first point.
  const auto ref = test::reference_from_json_text(test::read_file(dir + "/hull.json"));
  EXPECT_GT(ref.u_end(), ref.u_begin());
}

TEST(Cli, ParametersOptionReachesTheFitAndTheReport) {
  const std::string dir = test::temp_dir();
  const std::string hull = "'" + test::example("ship_px121_stations.rows") + "'";
  // The two-stage method (the default surface search tries every rule itself).
  const auto paper =
      run_cli("fit " + hull + " --method sfit01 --tol-rel 1e-2 -q --report '" + dir + "/p.json'");
  const auto chord = run_cli("fit " + hull + " --method sfit01 --tol-rel 1e-2 --parameters chord " +
                             "--report '" + dir + "/c.json'");
  ASSERT_EQ(paper.exit_code, 0) << paper.err;
  ASSERT_EQ(chord.exit_code, 0) << chord.err;
  EXPECT_NE(chord.err.find("; chord parameters"), std::string::npos) << chord.err;
  const auto p = nlohmann::json::parse(test::read_file(dir + "/p.json"));
  const auto c = nlohmann::json::parse(test::read_file(dir + "/c.json"));
  EXPECT_EQ(p["parameters"], "paper");
  EXPECT_EQ(c["parameters"], "chord");
  EXPECT_TRUE(c["within_tolerance"].get<bool>());
  // The hull's stations are sampled unevenly: chord length needs fewer control points.
  const int np = p["control_points"][0].get<int>() * p["control_points"][1].get<int>();
  const int nc = c["control_points"][0].get<int>() * c["control_points"][1].get<int>();
  EXPECT_LT(nc, np);
}

TEST(Cli, ReadsStandardInputAndPerAxisTolerance) {
  const std::string dir = test::temp_dir();
  const auto r =
      run_cli("fit - -o '" + dir + "/s.json' --tol 0.1,0.2,0.001 --degree-u 2 --degree-v 1 -q",
              "0 0 0\n1 0 0.1\n2 0 0\n3 0 0.2\n\n0 1 0\n1 1 0.3\n2 1 0\n3 1 0.1\n\n0 2 0\n3 2 0\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // -q
  const auto j = nlohmann::json::parse(test::read_file(dir + "/s.json"));
  EXPECT_EQ(j["degree"], nlohmann::json({2, 1}));
  EXPECT_EQ(j["report"]["tolerance"], nlohmann::json({0.1, 0.2, 0.001}));
}

TEST(Cli, ClosedRowsGivePeriodicU) {
  const std::string dir = test::temp_dir();
  const auto r = run_cli("fit '" + test::example("d150_wing.rows") + "' --closed u -o '" + dir +
                         "/w.json' -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(test::read_file(dir + "/w.json"));
  EXPECT_EQ(j["periodic"], nlohmann::json({true, false}));
}

TEST(Cli, ExitCodesAndOneLineErrors) {
  const std::string dir = test::temp_dir();
  const std::string hull = "'" + test::example("ship_px121_stations.rows") + "'";
  struct Case {
    std::string args;
    int code;
    std::string needle;
  };
  const Case cases[] = {
      {"fit " + hull + " -o " + dir + "/a.json --degree 0", 2,
       "--degree: degree 0 is out of range"},
      {"fit " + hull + " -o " + dir + "/a.json --degree 25", 2, "--degree: degree 25"},
      {"fit " + hull + " -o " + dir + "/a.json --tol -1", 2, "--tol"},
      {"fit " + hull + " -o " + dir + "/a.json --closed w", 2, "--closed"},
      {"fit " + dir + "/missing.rows -o " + dir + "/a.json", 3, "missing.rows"},
      {"fit " + hull + " -o /nonexistent-sfit-dir/a.json", 6, "does not exist"},
      {"fit " + hull + " -o " + dir + "/a.xyz", 2, "unknown output extension"},
      {"fit", 2, ""},
  };
  for (const auto& c : cases) {
    const auto r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, c.code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line: " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/a.json"));
  }
  // A syntax error names file:line:column.
  test::write_file(dir + "/bad.rows", "0 0 0\n1 1 1\n\n2 2 oops\n");
  const auto r = run_cli("fit " + dir + "/bad.rows -o " + dir + "/a.json");
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find("bad.rows:4:5:"), std::string::npos) << r.err;
}

TEST(Cli, HelpHasExamples) {
  const auto r = run_cli("fit --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("Examples:"), std::string::npos);
  EXPECT_NE(r.out.find("--closed"), std::string::npos);
}

}  // namespace
}  // namespace sfit
