#include "sfit/io/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "sfit/error.h"
#include "test_support.h"

namespace sfit::io {
namespace {

std::size_t files_in(const std::string& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFile, WritesAndReplaces) {
  const std::string dir = test::temp_dir();
  const std::string path = dir + "/out.txt";
  write_file_atomically(path, [](std::ostream& o) { o << "first"; });
  EXPECT_EQ(test::read_file(path), "first");
  write_file_atomically(path, [](std::ostream& o) { o << "second"; });
  EXPECT_EQ(test::read_file(path), "second");
  EXPECT_EQ(files_in(dir), 1u);  // no temporary left behind
}

TEST(AtomicFile, FailureKeepsTheOldFileAndLeavesNoTemporary) {
  const std::string dir = test::temp_dir();
  const std::string path = dir + "/out.txt";
  test::write_file(path, "precious");
  EXPECT_THROW(write_file_atomically(path,
                                     [](std::ostream& o) {
                                       o << "half";
                                       throw std::runtime_error("writer died");
                                     }),
               std::runtime_error);
  EXPECT_EQ(test::read_file(path), "precious");
  EXPECT_EQ(files_in(dir), 1u);
  EXPECT_THROW(
      write_via_temporary(path, [](const std::string&) { throw std::runtime_error("no"); }),
      std::runtime_error);
  EXPECT_EQ(test::read_file(path), "precious");
  EXPECT_EQ(files_in(dir), 1u);
}

TEST(AtomicFile, MissingFolderIsAnOutputError) {
  try {
    write_file_atomically("/nonexistent-sfit-folder/out.json", [](std::ostream& o) { o << "x"; });
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kOutputWrite);
    EXPECT_EQ(e.exit_code(), 6);
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
}

}  // namespace
}  // namespace sfit::io
