// Failures at the very end of a run: a rename of io::OutputBatch::commit() that cannot or does
// not succeed (every output or none: the ones renamed before it get their old content back),
// someone else's file in a sticky folder (refused before anything is read), and standard
// output that cannot be written (a closed pipe, a full device): a line and exit 6, never a
// silent death by SIGPIPE or an exit 0.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "atomic_file_testing.h"
#include "sfit/error.h"
#include "sfit/io/atomic_file.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace sfit::test {
namespace {

std::map<std::string, std::string> contents(const std::string& dir) {
  std::map<std::string, std::string> m;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) m[e.path().filename().string()] = read_file(e.path().string());
  return m;
}

int shell(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

void stage_three(const std::string& dir) {
  io::write_file_atomically(dir + "/a.txt", [](std::ostream& o) { o << "new a"; });
  io::write_file_atomically(dir + "/b.txt", [](std::ostream& o) { o << "new b"; });
  io::write_file_atomically(dir + "/c.txt", [](std::ostream& o) { o << "new c"; });
}

TEST(OutputBatch, ARenameThatWouldFailIsFoundBeforeTheFirstRename) {
  const std::string dir = temp_dir();
  write_file(dir + "/a.txt", "old a");
  try {
    io::OutputBatch batch;
    stage_three(dir);
    fs::create_directory(dir + "/c.txt");  // in the way of the third rename, made meanwhile
    batch.commit();
    FAIL() << "commit() renamed onto a directory";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kOutputWrite);
    EXPECT_EQ(std::string(e.what()), dir + "/c.txt: cannot write output: it is a directory");
  }
  EXPECT_EQ(contents(dir), (std::map<std::string, std::string>{{"a.txt", "old a"}}));
  EXPECT_TRUE(fs::is_directory(dir + "/c.txt"));
}

TEST(OutputBatch, AFailedRenameRestoresTheOutputsRenamedBeforeIt) {
  const std::string dir = temp_dir();
  write_file(dir + "/a.txt", "old a");  // replaced by rename 0, restored
  write_file(dir + "/c.txt", "old c");  // rename 2 fails: untouched
  const auto ino = fs::hard_link_count(dir + "/a.txt");
  try {
    io::OutputBatch batch;
    stage_three(dir);  // b.txt is new: rename 1 makes it, the roll-back removes it
    io::testing::fail_rename_at(2, EIO);
    batch.commit();
    FAIL() << "the injected failure did not happen";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kOutputWrite);
    EXPECT_EQ(std::string(e.what()),
              dir +
                  "/c.txt: cannot write output: Input/output error; the outputs renamed "
                  "before it were restored");
  }
  EXPECT_EQ(contents(dir),
            (std::map<std::string, std::string>{{"a.txt", "old a"}, {"c.txt", "old c"}}));
  EXPECT_EQ(fs::hard_link_count(dir + "/a.txt"), ino) << "no copy aside left linked";
  // The next batch works as usual (the injection fired once).
  {
    io::OutputBatch batch;
    stage_three(dir);
    batch.commit();
  }
  EXPECT_EQ(contents(dir), (std::map<std::string, std::string>{
                               {"a.txt", "new a"}, {"b.txt", "new b"}, {"c.txt", "new c"}}));
}

TEST(OutputBatch, TheFirstRenameFailingChangesNothing) {
  const std::string dir = temp_dir();
  write_file(dir + "/a.txt", "old a");
  try {
    io::OutputBatch batch;
    stage_three(dir);
    io::testing::fail_rename_at(0, ENOSPC);
    batch.commit();
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), dir + "/a.txt: cannot write output: No space left on device");
  }
  EXPECT_EQ(contents(dir), (std::map<std::string, std::string>{{"a.txt", "old a"}}));
}

// As user nobody (the test drops to it with setpriv, so it needs root): a file of root's in a
// sticky folder cannot be replaced; refused before the input is read, the other output never
// made.
TEST(OutputPlan, SomeoneElsesFileInAStickyFolderIsRefusedFirst) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to own a file nobody cannot replace";
  const std::string dir = temp_dir();
  const std::string sticky = dir + "/sticky";
  fs::create_directory(sticky);
  ASSERT_EQ(::chmod(sticky.c_str(), 01777), 0);
  ASSERT_EQ(::chmod(dir.c_str(), 0755), 0);
  write_file(sticky + "/taken.json", "root's file");
  const std::string err = dir + "/err";
  const int code =
      shell("setpriv --reuid=65534 --regid=65534 --clear-groups " + shell_quoted(SFIT_CLI) +
            " fit " + shell_quoted(good_rows()) + " -o " + shell_quoted(sticky + "/new.json") +
            " -o " + shell_quoted(sticky + "/taken.json") + " 2>" + shell_quoted(err));
  EXPECT_EQ(code, 6);
  EXPECT_EQ(read_file(err), "sfit: error: " + sticky +
                                "/taken.json: cannot write output: it belongs to another user "
                                "(uid 0) in the sticky folder '" +
                                sticky + "', where only its owner may replace it\n");
  EXPECT_EQ(contents(sticky), (std::map<std::string, std::string>{{"taken.json", "root's file"}}));
}

TEST(StandardOutput, AClosedPipeIsAWriteErrorWithItsLine) {
  const std::string dir = temp_dir();
  // The reader exits at once; sfit writes the JSON after the fit, into the closed pipe.
  const int code =
      shell("( " + shell_quoted(SFIT_CLI) + " fit " + shell_quoted(good_rows()) + " -o - 2>" +
            shell_quoted(dir + "/err") + "; echo $? >" + shell_quoted(dir + "/code") + " ) | true");
  EXPECT_EQ(code, 0);
  EXPECT_EQ(read_file(dir + "/code"), "6\n") << "not killed by SIGPIPE (141)";
  const std::string err = read_file(dir + "/err");
  EXPECT_NE(err.find("sfit: error: standard output: cannot write output: Broken pipe\n"),
            std::string::npos)
      << err;
}

TEST(StandardOutput, AFullDeviceIsNotSuccess) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const std::string dir = temp_dir();
  for (const std::string args : {"formats", "--help", "--version", "fit --help"}) {
    SCOPED_TRACE(args);
    const int code =
        shell(shell_quoted(SFIT_CLI) + " " + args + " >/dev/full 2>" + shell_quoted(dir + "/err"));
    EXPECT_EQ(code, 6);
    EXPECT_EQ(read_file(dir + "/err"),
              "sfit: error: standard output: cannot write output: No space left on device\n");
  }
}

// Out of memory (std::bad_alloc) is exit 10 with the command and input named, never exit 8:
// the address space limited (ulimit -v) from where the program barely loads upwards until one
// runs out, on two rows of 30000 points whose fit needs some 100 MB. Not in AddressSanitizer
// builds: their shadow memory cannot be mapped under an address-space limit at all (the
// release build's run of this test is the one that counts).
TEST(OutOfMemory, IsExitTenWithItsPlace) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer cannot run under ulimit -v (its shadow memory)";
#endif
  const std::string dir = temp_dir();
  std::string rows;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 30000; ++i)
      rows += std::to_string(i * 1e-3) + " " + std::to_string(j) + " " +
              std::to_string(std::sin(i * 1e-4) + (i == 15000 ? 5.0 : 0.0)) + "\n";
    rows += "\n";
  }
  write_file(dir + "/long.rows", rows);
  int tens = 0;
  for (int mb = 60; mb <= 180; mb += 30) {
    SCOPED_TRACE(std::to_string(mb) + " MB");
    const int code =
        shell("cd " + shell_quoted(dir) + " && ulimit -v " + std::to_string(mb * 1024) + " && " +
              shell_quoted(SFIT_CLI) + " fit long.rows -o out.json -q 2>err");
    const std::string err = read_file(dir + "/err");
    if (code == 127) continue;  // the loader could not map the libraries: sfit never ran
    EXPECT_TRUE(code == 0 || code == 10) << code << ": " << err;
    if (code != 10) continue;
    ++tens;  // one is enough: the limits above it only cost a whole fit each
    EXPECT_EQ(err,
              "sfit: error: fit long.rows: out of memory: the input or the options need more "
              "memory than this process can have\n");
    EXPECT_FALSE(fs::exists(dir + "/out.json"));
    break;
  }
  EXPECT_GT(tens, 0) << "no limit made the fit run out of memory";
}

}  // namespace
}  // namespace sfit::test
