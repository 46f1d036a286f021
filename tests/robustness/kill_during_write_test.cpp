// Nothing lost: sfit writes every output to a temporary file beside the target and
// renames it, so killing the process in the middle of a large write leaves an existing output
// exactly as it was. SIGKILL gives the process no chance to clean up, so the partial
// temporary file "OUT.sfit-XXXXXX" stays behind; it never has the target's name.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "sfit/error.h"
#include "sfit/io/surface_json.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace sfit::test {
namespace {

void write_rows(const std::string& path, int rows, int points) {
  std::ofstream f(path);
  f.precision(12);
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < points; ++i)
      f << i << ' ' << j << ' ' << std::sin(0.03 * i) * std::cos(0.037 * j) << '\n';
    f << '\n';
  }
}

std::vector<std::string> temporaries(const std::string& dir, const std::string& target) {
  std::vector<std::string> out;
  const std::string prefix = fs::path(target).filename().string() + ".sfit-";
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind(prefix, 0) == 0) out.push_back(e.path().string());
  return out;
}

pid_t spawn_fit(const std::string& in, const std::string& out) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(SFIT_CLI, "sfit", "fit", in.c_str(), "--tol", "0", "-o", out.c_str(), "-q",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

TEST(NothingLost, KillDuringALargeWriteLeavesTheOldOutputIntact) {
  const std::string dir = temp_dir();
  const std::string small = dir + "/small.rows", big = dir + "/big.rows";
  const std::string out = dir + "/out.json";
  write_rows(small, 5, 6);
  write_rows(big, 400, 400);  // T = 0: about 390 x 390 control points, a 9 MB JSON file
  ASSERT_EQ(run_cli("fit '" + small + "' -o '" + out + "' -q").exit_code, 0);
  const std::string old = read_file(out);
  ASSERT_FALSE(old.empty());

  bool killed_mid_write = false;
  for (int attempt = 0; attempt < 12 && !killed_mid_write; ++attempt) {
    const pid_t pid = spawn_fit(big, out);
    ASSERT_GT(pid, 0);
    int status = 0;
    bool exited = false;
    while (!killed_mid_write && !exited) {
      for (const auto& t : temporaries(dir, out)) {
        std::error_code ec;
        if (fs::file_size(t, ec) > 0 && !ec) {
          ::kill(pid, SIGKILL);
          killed_mid_write = true;
          break;
        }
      }
      if (!killed_mid_write) {
        exited = ::waitpid(pid, &status, WNOHANG) == pid;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    }
    if (killed_mid_write) {
      ASSERT_EQ(::waitpid(pid, &status, 0), pid);
      // On a loaded machine the kill can arrive after the write finished: then nothing was
      // interrupted (the process exited, no temporary is left, or the one left is whole,
      // killed between its last byte and the rename): try again.
      bool whole = false;
      for (const auto& t : temporaries(dir, out)) {
        try {
          io::read_surface_json(t);
          whole = true;
        } catch (const Error&) {
        }
      }
      if (!WIFSIGNALED(status) || temporaries(dir, out).empty() || whole) {
        killed_mid_write = false;
        write_file(out, old);
        for (const auto& t : temporaries(dir, out)) fs::remove(t);
        continue;
      }
      ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    } else {
      // It finished before we saw the write: put the old file back and try again.
      ASSERT_TRUE(WIFEXITED(status)) << status;
      write_file(out, old);
      for (const auto& t : temporaries(dir, out)) fs::remove(t);
    }
  }
  ASSERT_TRUE(killed_mid_write) << "the write was never caught in progress";

  EXPECT_EQ(read_file(out), old) << "the old output was touched";
  const auto left = temporaries(dir, out);
  ASSERT_EQ(left.size(), 1u) << "SIGKILL leaves exactly the one partial temporary file";
  EXPECT_GT(fs::file_size(left[0]), 0u);
  EXPECT_THROW(io::read_surface_json(left[0]), Error) << "the temporary is partial";

  // The next run replaces the output as usual; the stale temporary does not get in its way.
  ASSERT_EQ(run_cli("fit '" + small + "' --tol 0.01 -o '" + out + "' -q").exit_code, 0);
  EXPECT_NO_THROW(io::read_surface_json(out));
  EXPECT_NE(read_file(out), old);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sfit::test
