// The CLI's exchange formats end to end: several -o in one run, convert, CSV and STEP inputs,
// the JSON reloading bit for bit, and the errors (exit codes, nothing written).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "exchange_cases.h"
#include "sfit/io/surface_json.h"
#include "test_support.h"

namespace sfit {
namespace {

namespace fs = std::filesystem;
using test::run_cli;
using test::shell_quoted;

TEST(ExchangeCli, OneFitWritesEveryFormat) {
  const std::string dir = test::temp_dir();
  std::string outs;
  for (const char* e : {"json", "step", "stp", "igs", "iges", "obj", "stl", "ply", "vtk", "vts"})
    outs += " -o " + shell_quoted(dir + "/wing." + e);
  const auto r = run_cli("fit " + shell_quoted(test::example("d150_wing.rows")) +
                         " --closed u --fields" + outs);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* e : {"json", "step", "stp", "igs", "iges", "obj", "stl", "ply", "vtk", "vts"}) {
    EXPECT_GT(fs::file_size(dir + "/wing." + e), 1000u) << e;
    EXPECT_NE(r.err.find("wrote " + dir + "/wing." + e), std::string::npos) << e;
  }
  EXPECT_TRUE(r.out.empty()) << "OpenCASCADE chatter on stdout: " << r.out.substr(0, 200);
  // No temporary files left behind.
  for (const auto& f : fs::directory_iterator(dir))
    EXPECT_EQ(f.path().string().find(".sfit-"), std::string::npos) << f.path();
  // .obj is a triangle mesh with normals (and stderr says so); --obj-freeform gives the
  // exact free-form surface.
  EXPECT_NE(r.err.find("wrote " + dir + "/wing.obj (triangle mesh, "), std::string::npos) << r.err;
  const std::string obj = test::read_file(dir + "/wing.obj");
  EXPECT_NE(obj.find("\nvn "), std::string::npos);
  EXPECT_NE(obj.find("\nf 1//1 "), std::string::npos);
  EXPECT_EQ(obj.find("cstype"), std::string::npos);
  const auto m =
      run_cli("fit " + shell_quoted(test::example("d150_wing.rows")) +
              " --closed u --method sfit01 --obj-freeform -o " + shell_quoted(dir + "/free.obj"));
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_NE(test::read_file(dir + "/free.obj").find("cstype bspline"), std::string::npos);
  EXPECT_NE(m.err.find("(free-form B-spline surface, 14 x 4 control points"), std::string::npos)
      << m.err;
}

TEST(ExchangeCli, ConvertReexportsAndJsonReloadsBitForBit) {
  const std::string dir = test::temp_dir();
  for (const auto* c : test::must_pass_cases()) {
    SCOPED_TRACE(c->name);
    // The library's JSON of each surface reloads to identical doubles.
    io::write_surface_json(dir + "/s.json", c->fit.surface, &c->fit.report);
    const Surface back = io::read_surface_json(dir + "/s.json");
    ASSERT_EQ(back.control.size(), c->fit.surface.control.size());
    EXPECT_EQ(std::memcmp(back.control.data(), c->fit.surface.control.data(),
                          back.control.size() * sizeof(Point)),
              0);
    EXPECT_EQ(back.periodic_u, c->fit.surface.periodic_u);
    EXPECT_EQ(back.periodic_v, c->fit.surface.periodic_v);
    // convert: JSON -> JSON is the same surface; JSON -> STEP/IGES/STL works.
    const auto r = run_cli("convert " + shell_quoted(dir + "/s.json") + " -o " +
                           shell_quoted(dir + "/t.json") + " -o " + shell_quoted(dir + "/t.step") +
                           " -o " + shell_quoted(dir + "/t.igs") + " -o " +
                           shell_quoted(dir + "/t.stl") + " --units m");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Surface again = io::read_surface_json(dir + "/t.json");
    EXPECT_EQ(
        std::memcmp(again.control.data(), back.control.data(), back.control.size() * sizeof(Point)),
        0);
    EXPECT_NE(test::read_file(dir + "/t.step").find("SI_UNIT($,.METRE.)"), std::string::npos);
  }
}

TEST(ExchangeCli, FitsCsvAndStepSectionInputs) {
  const std::string dir = test::temp_dir();
  // The ship stations as CSV with a row column.
  const Rows rows = test::load_rows(test::example("ship_px121_stations.rows"));
  std::string csv = "row,x,y,z\n";
  char buf[160];
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (const Point& p : rows[j]) {
      std::snprintf(buf, sizeof buf, "%zu,%.17g,%.17g,%.17g\n", j, p.x(), p.y(), p.z());
      csv += buf;
    }
  test::write_file(dir + "/ship.csv", csv);
  auto r = run_cli("fit " + shell_quoted(dir + "/ship.csv") + " -o " +
                   shell_quoted(dir + "/a.json") + " -o " + shell_quoted(dir + "/a.step"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("11 rows, 90 points"), std::string::npos) << r.err;
  // Our own STEP output holds a face, not sections: a clear data error.
  r = run_cli("fit " + shell_quoted(dir + "/a.step") + " -o " + shell_quoted(dir + "/b.json"));
  EXPECT_EQ(r.exit_code, 5) << r.err;
  EXPECT_NE(r.err.find("no section curves"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/b.json"));
}

TEST(ExchangeCli, ErrorsExitWithTheirCodeAndWriteNothing) {
  const std::string dir = test::temp_dir();
  const std::string in = shell_quoted(test::example("ship_px121_stations.rows"));
  auto r = run_cli("fit " + in + " -o " + shell_quoted(dir + "/x.dxf"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown output extension 'dxf'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(".step"), std::string::npos) << "the known extensions are listed";
  r = run_cli("fit " + in + " --units parsec -o " + shell_quoted(dir + "/x.step"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--units: unknown length unit 'parsec'"), std::string::npos) << r.err;
  r = run_cli("fit " + in + " --mesh-density 1 -o " + shell_quoted(dir + "/x.stl"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--mesh-density"), std::string::npos) << r.err;
  r = run_cli("fit " + in + " -o " + shell_quoted(dir + "/no/such/x.igs"));
  EXPECT_EQ(r.exit_code, 6);
  test::write_file(dir + "/bad.csv", "x,y,z\n1,2,3\n1,2,oops\n");
  r = run_cli("fit " + shell_quoted(dir + "/bad.csv") + " -o " + shell_quoted(dir + "/x.json"));
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find(dir + "/bad.csv:3:5: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'oops' is not a number"), std::string::npos) << r.err;
  test::write_file(dir + "/bad.step", "ISO-10303-21;\nnonsense\n");
  r = run_cli("fit " + shell_quoted(dir + "/bad.step") + " -o " + shell_quoted(dir + "/x.json"));
  EXPECT_EQ(r.exit_code, 4) << r.err;
  r = run_cli("fit " + shell_quoted(dir + "/missing.iges") + " -o " +
              shell_quoted(dir + "/x.json"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  // An existing output survives a failed run.
  test::write_file(dir + "/keep.stl", "old");
  r = run_cli("fit " + in + " --mesh-density 0,5 -o " + shell_quoted(dir + "/keep.stl"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(test::read_file(dir + "/keep.stl"), "old");
  for (const auto& f : fs::directory_iterator(dir)) {
    const std::string n = f.path().filename().string();
    EXPECT_TRUE(n == "bad.csv" || n == "bad.step" || n == "keep.stl") << n;
  }
}

// STEP and IGES come from a module loaded on first use (src/exchange/cad_module.h): the CLI
// itself does not link OpenCASCADE, and where the module is missing a run that asks for STEP is
// refused before any work, writing nothing.
TEST(ExchangeCli, TheCadModuleLoadsOnlyWhenAskedFor) {
  // What the program links, as the dynamic loader resolves it (ldd).
  std::string linked;
  if (FILE* p = ::popen(("ldd " + shell_quoted(SFIT_CLI) + " 2>&1").c_str(), "r")) {
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) linked.append(buf, n);
    ::pclose(p);
  }
  EXPECT_NE(linked.find("libc.so"), std::string::npos) << linked;
  EXPECT_EQ(linked.find("libTK"), std::string::npos) << "OpenCASCADE linked:\n" << linked;

  const std::string dir = test::temp_dir();
  const std::string in = shell_quoted(test::example("ship_px121_stations.rows"));
  test::write_file(dir + "/keep.step", "old");
  for (const std::string& module : {dir + "/no/libsfit_cad.so", test::good_rows()}) {
    ::setenv("SFIT_CAD_MODULE", module.c_str(), 1);
    const auto r = run_cli("fit " + in + " -o " + shell_quoted(dir + "/x.json") + " -o " +
                           shell_quoted(dir + "/keep.step"));
    const auto formats = run_cli("formats");
    const auto read = run_cli(
        "fit " + shell_quoted(std::string(SFIT_TESTS_DIR) + "/bad_input/closed_sections.igs") +
        " -o " + shell_quoted(dir + "/y.json"));
    ::unsetenv("SFIT_CAD_MODULE");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("-o: STEP and IGES need sfit's CAD module (libsfit_cad.so"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(module), std::string::npos) << "names where it looked: " << r.err;
    EXPECT_EQ(read.exit_code, 2) << read.err;
    EXPECT_NE(formats.out.find("no module"), std::string::npos) << formats.out;
    EXPECT_NE(read.err.find("closed_sections.igs: STEP and IGES need sfit's CAD module"),
              std::string::npos)
        << "names the file that asked for it: " << read.err;
    EXPECT_EQ(test::read_file(dir + "/keep.step"), "old");
    EXPECT_FALSE(fs::exists(dir + "/x.json")) << "nothing is written when one output cannot be";
    EXPECT_FALSE(fs::exists(dir + "/y.json"));
  }
  EXPECT_EQ(run_cli("formats").out.find("no module"), std::string::npos);
  // Found (beside the build or the install), the same run writes both.
  const auto r = run_cli("fit " + in + " -q -o " + shell_quoted(dir + "/x.json") + " -o " +
                         shell_quoted(dir + "/keep.step"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(test::read_file(dir + "/keep.step").find("ISO-10303-21"), std::string::npos);
}

}  // namespace
}  // namespace sfit
