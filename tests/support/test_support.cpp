#include "test_support.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <stdexcept>

#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "reference_eval.h"
#include "sfit/io/rows_reader.h"
#include "surface_json_value.h"

namespace sfit::test {

std::string shared_data(const std::string& name) {
  static const std::pair<const char*, const char*> kStandIns[] = {
      {"teapot_body.rows", "ring_body.rows"},
      {"teapot_handle.rows", "bent_tube.rows"},
      {"teapot_spout_small.rows", "spout_tube.rows"},
      {"volcano.rows", "height_field.rows"},
      {"volcano_small.rows", "height_field_small.rows"}};
  std::string file = name;
  for (const auto& [model, stand_in] : kStandIns)
    if (name == model) file = stand_in;
  const std::string p = example(file);
  if (!std::filesystem::exists(p)) throw std::runtime_error("data set " + p + " not found");
  return p;
}

std::string example(const std::string& name) {
  return std::string(SFIT_EXAMPLES_DIR) + "/" + name;
}

Rows load_rows(const std::string& path) {
  return io::read_rows(path).rows;
}

Rows sample_rows(const std::function<Point(double, double)>& f, const std::vector<int>& counts,
                 bool closed_u, bool closed_v) {
  Rows rows;
  const int M = static_cast<int>(counts.size());
  for (int j = 0; j < M; ++j) {
    const double t = closed_v ? static_cast<double>(j) / M : static_cast<double>(j) / (M - 1);
    const int n = counts[j];
    for (int k = 0; k < n; ++k) {
      const double s = n == 1     ? 0.0
                       : closed_u ? static_cast<double>(k) / n
                                  : static_cast<double>(k) / (n - 1);
      rows.push_point(f(s, t));
    }
    rows.end_row();
  }
  return rows;
}

namespace {
// Every temp_dir() made by this test program, removed when it exits (set SFIT_KEEP_TEST_DIRS
// to keep them for a look after a failure).
struct TempDirs {
  std::vector<std::filesystem::path> made;
  ~TempDirs() {
    if (std::getenv("SFIT_KEEP_TEST_DIRS")) return;
    std::error_code ec;
    for (const auto& d : made) std::filesystem::remove_all(d, ec);
  }
};
TempDirs& temp_dirs() {
  static TempDirs dirs;
  return dirs;
}
}  // namespace

std::string temp_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "sfit";
  for (char& c : name)
    if (c == '/') c = '_';
  const auto dir = std::filesystem::temp_directory_path() /
                   ("sfit-test-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  temp_dirs().made.push_back(dir);
  return dir.string();
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

Run run_cli(const std::string& args, const std::string& stdin_text) {
  // Its own folder for the captured streams: never the calling test's temp_dir().
  std::string tmpl = (std::filesystem::temp_directory_path() / "sfit-run-XXXXXX").string();
  if (!::mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
  const std::string dir = tmpl;
  const std::string in = dir + "/stdin", out = dir + "/stdout", err = dir + "/stderr";
  write_file(in, stdin_text);
  const std::string cmd =
      std::string("'") + SFIT_CLI + "' " + args + " <'" + in + "' >'" + out + "' 2>'" + err + "'";
  const int status = std::system(cmd.c_str());
  Run r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = read_file(out);
  r.err = read_file(err);
  std::filesystem::remove_all(dir);
  return r;
}

Point reference_deviation(const FitResult& fit, const Rows& rows, int stride) {
  const auto ref = reference_from_json_text(io::surface_to_json(fit.surface).dump());
  Point worst = Point::Zero();
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (std::size_t k = 0; k < rows[j].size(); k += static_cast<std::size_t>(stride)) {
      const auto s =
          ref.evaluate(fit.u[rows.offsets()[j] + k], fit.point_v(j, rows.offsets()[j] + k));
      worst = worst.cwiseMax((Point(s[0], s[1], s[2]) - rows[j][k]).cwiseAbs());
    }
  return worst;
}

void expect_same_surface(const FitResult& a, const FitResult& b) {
  ASSERT_EQ(a.surface.count_u, b.surface.count_u);
  ASSERT_EQ(a.surface.count_v, b.surface.count_v);
  ASSERT_EQ(a.surface.control.size(), b.surface.control.size());
  EXPECT_EQ(0, std::memcmp(a.surface.control.data(), b.surface.control.data(),
                           a.surface.control.size() * sizeof(Point)));
  EXPECT_EQ(a.u, b.u);
  EXPECT_EQ(a.v, b.v);
}

std::string shell_quoted(const std::string& s) {
  return "'" + s + "'";
}

std::string good_rows() {
  return std::string(SFIT_TESTS_DIR) + "/bad_input/good.rows";
}

}  // namespace sfit::test
