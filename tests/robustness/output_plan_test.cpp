// The output plan (apps/sfit/output_plan.h) and io::OutputBatch: no output ever replaces an
// input, whatever its spelling or link; one file is never named twice; every output or none
// is written, also when the disk fills up on the second one or a late output is refused;
// '-o -' puts the JSON on standard output.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "sfit/error.h"
#include "sfit/io/atomic_file.h"
#include "sfit/io/surface_json.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace sfit::test {
namespace {

std::map<std::string, std::string> contents(const std::string& dir) {
  std::map<std::string, std::string> m;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && !e.is_symlink()) m[e.path().string()] = read_file(e.path().string());
  return m;
}

TEST(OutputBatch, AllOrNothing) {
  const std::string dir = temp_dir();
  write_file(dir + "/a.txt", "old a");
  {
    io::OutputBatch batch;
    io::write_file_atomically(dir + "/a.txt", [](std::ostream& o) { o << "new a"; });
    io::write_file_atomically(dir + "/b.txt", [](std::ostream& o) { o << "new b"; });
    EXPECT_EQ(read_file(dir + "/a.txt"), "old a") << "nothing renamed before commit()";
    EXPECT_FALSE(fs::exists(dir + "/b.txt"));
  }  // no commit: a later output failed
  EXPECT_EQ(contents(dir), (std::map<std::string, std::string>{{dir + "/a.txt", "old a"}}));
  {
    io::OutputBatch batch;
    io::write_file_atomically(dir + "/a.txt", [](std::ostream& o) { o << "new a"; });
    io::write_file_atomically(dir + "/b.txt", [](std::ostream& o) { o << "new b"; });
    batch.commit();
  }
  EXPECT_EQ(contents(dir), (std::map<std::string, std::string>{{dir + "/a.txt", "new a"},
                                                               {dir + "/b.txt", "new b"}}));
}

TEST(OutputPlan, NoSpellingOrLinkOfTheInputIsWritten) {
  const std::string dir = temp_dir();
  fs::copy_file(good_rows(), dir + "/in.rows");
  fs::create_hard_link(dir + "/in.rows", dir + "/hard.json");
  fs::create_symlink(dir + "/in.rows", dir + "/soft.json");
  fs::create_directories(dir + "/sub");
  const auto before = contents(dir);
  struct Case {
    std::string args, error;
  };
  const std::string in = dir + "/in.rows";
  const std::vector<Case> cases = {
      {"fit " + shell_quoted(in) + " -o " + shell_quoted(dir + "/hard.json"),
       "-o: '" + dir + "/hard.json' is the input file '" + in +
           "': sfit never writes over an input"},
      {"fit " + shell_quoted(in) + " -o " + shell_quoted(dir + "/soft.json"),
       "-o: '" + dir + "/soft.json' is the input file '" + in +
           "': sfit never writes over an input"},
      {"fit " + shell_quoted(in) + " -o " + shell_quoted(dir + "/a.json") + " --report " +
           shell_quoted(dir + "/sub/../in.rows"),
       "--report: '" + dir + "/sub/../in.rows' is the input file '" + in +
           "': sfit never writes over an input"},
      {"fit " + shell_quoted(in) + " -o " + shell_quoted(dir + "/a.json") + " --report " +
           shell_quoted(dir + "/sub/../a.json"),
       "--report: '" + dir + "/sub/../a.json' is already the output of -o (as '" + dir +
           "/a.json'): give each output once"},
      {"convert " + shell_quoted(dir + "/hard.json") + " -o " + shell_quoted(dir + "/soft.json"),
       "-o: '" + dir + "/soft.json' is the input file '" + dir +
           "/hard.json': sfit never writes over an input"},
  };
  for (const auto& c : cases) {
    const sfit::test::Run r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_EQ(r.err, "sfit: error: " + c.error + "\n");
    EXPECT_EQ(contents(dir), before) << c.args;
  }
  // Standard input redirected from a file protects that file too.
  const std::string err = dir + "/../stdin-case.err";
  const int status =
      std::system((shell_quoted(SFIT_CLI) + " fit - -o " + shell_quoted(dir + "/hard.json") + " <" +
                   shell_quoted(in) + " 2>" + shell_quoted(err))
                      .c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_EQ(read_file(err),
            "sfit: error: -o: '" + dir +
                "/hard.json' is the input file 'standard input': sfit never writes over "
                "an input\n");
  EXPECT_EQ(contents(dir), before);
}

TEST(OutputPlan, ADeviceOrPipeIsNeverReplaced) {
  // The rename of a finished output would replace a FIFO (or /dev/null) by a plain file.
  const std::string dir = temp_dir();
  const std::string fifo = dir + "/pipe.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const sfit::test::Run r =
      run_cli("fit " + shell_quoted(good_rows()) + " --report " + shell_quoted(fifo));
  EXPECT_EQ(r.exit_code, 6) << r.err;
  EXPECT_EQ(r.err, "sfit: error: " + fifo +
                       ": cannot write output: it is not a regular file (a device, pipe or "
                       "socket); give '-' for standard output\n");
  struct stat st {};
  ASSERT_EQ(::stat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the pipe is still a pipe";
}

TEST(OutputPlan, ALateRefusalLeavesEveryOldFileAndNoNewOne) {
  const std::string dir = temp_dir();
  write_file(dir + "/in.rows",
             read_file(std::string(SFIT_TESTS_DIR) + "/bad_input/extent_1e100.rows"));
  write_file(dir + "/out.json", "old json");
  write_file(dir + "/report.json", "old report");
  const auto before = contents(dir);
  // The STL is refused only once the surface exists (float32 overflow): after the JSON and
  // the report were written to their temporaries.
  const sfit::test::Run r = run_cli(
      "fit " + shell_quoted(dir + "/in.rows") + " -o " + shell_quoted(dir + "/out.json") +
      " --report " + shell_quoted(dir + "/report.json") + " -o " + shell_quoted(dir + "/mesh.stl"));
  EXPECT_EQ(r.exit_code, 6) << r.err;
  EXPECT_EQ(r.err.find("sfit: wrote"), std::string::npos) << r.err;
  EXPECT_EQ(contents(dir), before);
}

TEST(OutputPlan, AFullDiskOnTheSecondOutputLeavesEveryOldFile) {
  if (::geteuid() != 0) GTEST_SKIP() << "mounting a small tmpfs needs root";
  const std::string dir = temp_dir();
  const std::string full = dir + "/small";
  fs::create_directories(full);
  if (::mount("tmpfs", full.c_str(), "tmpfs", 0, "size=16k") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (" << std::strerror(errno) << ")";
  write_file(dir + "/old.json", "old json");
  write_file(full + "/old.json", "old small json");
  const auto before = contents(dir);
  // The first output (a few KB) fits in the folder beside; the second, a dense mesh, fills
  // the 16 KiB tmpfs.
  const sfit::test::Run r =
      run_cli("fit " + shell_quoted(good_rows()) + " -o " + shell_quoted(dir + "/old.json") +
              " -o " + shell_quoted(full + "/old.json") + " -o " +
              shell_quoted(full + "/mesh.ply") + " --mesh-density 400");
  EXPECT_EQ(r.exit_code, 6) << r.err;
  EXPECT_NE(r.err.find("sfit: error: " + full + "/mesh.ply: cannot write output: "),
            std::string::npos)
      << r.err;
  EXPECT_EQ(contents(dir), before);
  ::umount(full.c_str());
}

TEST(OutputPlan, DashWritesTheJsonToStandardOutput) {
  const std::string dir = temp_dir();
  const sfit::test::Run r = run_cli("fit " + shell_quoted(good_rows()) + " -o - --report " +
                                    shell_quoted(dir + "/report.json"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  write_file(dir + "/stdout.json", r.out);
  const Surface s = io::read_surface_json(dir + "/stdout.json");
  EXPECT_GT(s.count_u, 0);
  EXPECT_NE(r.out.find("\"report\""), std::string::npos);
  EXPECT_NE(r.err.find("sfit: wrote the JSON to standard output\n"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("sfit: wrote " + dir + "/report.json\n"), std::string::npos) << r.err;
  // No output at all: the summary alone.
  const sfit::test::Run summary = run_cli("fit " + shell_quoted(good_rows()));
  EXPECT_EQ(summary.exit_code, 0) << summary.err;
  EXPECT_TRUE(summary.out.empty());
  EXPECT_NE(summary.err.find("every point within tolerance: yes"), std::string::npos);
}

}  // namespace
}  // namespace sfit::test
