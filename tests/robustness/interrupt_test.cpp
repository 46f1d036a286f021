// Ctrl-C and SIGTERM stop a CLI fit at once: nothing written, no temporary left, exit 128 +
// the signal (130, 143; docs/errors.md). On a terminal the fit shows a progress line first;
// with standard error not a terminal it is silent.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "test_support.h"

namespace fs = std::filesystem;

namespace sfit::test {
namespace {

using Clock = std::chrono::steady_clock;

// A grid whose noise is close to T = 0.5: the surface search tries many pairs (seconds).
void write_noisy_grid(const std::string& path, int rows, int points) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  unsigned long long state = 12345;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < points; ++i) {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      const double noise = 0.8 * (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5);
      std::fprintf(f, "%d %d %.6f\n", i, j, 10 * std::sin(0.01 * i) * std::cos(0.013 * j) + noise);
    }
    std::fputc('\n', f);
  }
  std::fclose(f);
}

bool nothing_written(const std::string& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename() != "in.rows") {
      ADD_FAILURE() << "left behind: " << e.path();
      return false;
    }
  return true;
}

// Reads what `fd` has within `seconds`, appending to `text`; false on end of file.
bool read_some(int fd, std::string& text, double seconds) {
  pollfd p{fd, POLLIN, 0};
  if (::poll(&p, 1, static_cast<int>(seconds * 1000)) <= 0) return true;
  char buf[4096];
  const ssize_t n = ::read(fd, buf, sizeof buf);
  if (n <= 0) return false;
  text.append(buf, static_cast<std::size_t>(n));
  return true;
}

class Interrupt : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(temp_dir());
    write_noisy_grid(*dir_ + "/in.rows", 900, 900);  // 4.5 s of fit on 2 cores
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static std::string* dir_;
};
std::string* Interrupt::dir_ = nullptr;

TEST_F(Interrupt, CtrlCOnATerminalStopsTheFitAfterItsProgressLine) {
  const std::string in = *dir_ + "/in.rows", out = *dir_ + "/out.json";
  int master = -1;
  const pid_t pid = ::forkpty(&master, nullptr, nullptr, nullptr);
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);  // standard error stays the terminal
    ::execl(SFIT_CLI, "sfit", "fit", in.c_str(), "--tol", "0.5", "-o", out.c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  std::string text;
  const auto start = Clock::now();
  // The progress line: "\rsfit: PHASE ..., N.N s\033[K", drawn once the fit has run a second.
  while (text.find("\033[K") == std::string::npos &&
         Clock::now() - start < std::chrono::seconds(300))
    if (!read_some(master, text, 0.1)) break;
  ASSERT_NE(text.find("\033[K"), std::string::npos) << "no progress line:\n" << text;
  const auto sent = Clock::now();
  ::kill(pid, SIGINT);
  // Everything it writes until it ends (the terminal then reads as closed).
  while (read_some(master, text, 1) && Clock::now() - sent < std::chrono::seconds(60)) {
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  std::printf("[ measured ] SIGINT to exit: %.3f s\n",
              std::chrono::duration<double>(Clock::now() - sent).count());
  ::close(master);
  ASSERT_TRUE(WIFEXITED(status)) << status;
  EXPECT_EQ(WEXITSTATUS(status), 130) << text;
  EXPECT_NE(text.find("sfit: error: " + in + ": interrupted by SIGINT; nothing written"),
            std::string::npos)
      << text;
  // The line was cleared before the error line.
  EXPECT_NE(text.find("\r\033[K"), std::string::npos) << text;
  EXPECT_TRUE(nothing_written(*dir_));
}

TEST_F(Interrupt, SigtermWithoutATerminalStopsASilentFit) {
  const std::string in = *dir_ + "/in.rows", out = *dir_ + "/out.json";
  int err[2];
  ASSERT_EQ(::pipe(err), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(err[1], 2);
    ::close(err[0]);
    ::execl(SFIT_CLI, "sfit", "fit", in.c_str(), "--tol", "0.5", "-o", out.c_str(), "--report",
            (*dir_ + "/report.json").c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(err[1]);
  std::string text;
  // The summary's second line is printed just before the fit starts.
  while (text.find("tolerance") == std::string::npos)
    if (!read_some(err[0], text, 1)) break;
  // Well into the fit (it takes seconds), with no progress line on a pipe.
  const auto until = Clock::now() + std::chrono::milliseconds(1000);
  while (Clock::now() < until) read_some(err[0], text, 0.05);
  const auto sent = Clock::now();
  ::kill(pid, SIGTERM);
  while (read_some(err[0], text, 1)) {
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  std::printf("[ measured ] SIGTERM to exit: %.3f s\n",
              std::chrono::duration<double>(Clock::now() - sent).count());
  ::close(err[0]);
  ASSERT_TRUE(WIFEXITED(status)) << status;
  EXPECT_EQ(WEXITSTATUS(status), 143) << text;
  EXPECT_NE(text.find("interrupted by SIGTERM; nothing written"), std::string::npos) << text;
  EXPECT_EQ(text.find('\r'), std::string::npos) << "a progress line on a pipe:\n" << text;
  EXPECT_TRUE(nothing_written(*dir_));
}

}  // namespace
}  // namespace sfit::test
