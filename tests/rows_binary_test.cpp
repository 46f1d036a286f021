#include "sfit/io/rows_binary.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "sfit/error.h"
#include "test_support.h"

namespace sfit::io {
namespace {

TEST(RowsBinary, RoundTripsBitForBit) {
  const Rows rows = read_rows(test::example("iea3p4mw_blade_ragged9.rows")).rows;
  const std::string path = test::temp_dir() + "/blade.srows";
  write_rows_binary(path, rows);
  EXPECT_EQ(std::filesystem::file_size(path), 32 + 8 * rows.size() + 24 * rows.total_points());
  const Rows back = read_rows_binary(path).rows;
  ASSERT_EQ(back.size(), rows.size());
  EXPECT_EQ(back.offsets(), rows.offsets());
  EXPECT_EQ(0, std::memcmp(back.points().data(), rows.points().data(), 24 * rows.total_points()));
}

ErrorCode code_of(const std::string& bytes) {
  const std::string path = test::temp_dir() + "/x.srows";
  test::write_file(path, bytes);
  try {
    read_rows_binary(path);
  } catch (const Error& e) {
    return e.code();
  }
  return ErrorCode::kInternal;
}

TEST(RowsBinary, RejectsBadFilesBeforeAllocating) {
  Rows rows;
  rows.add_row(std::vector<Point>{Point(0, 0, 0), Point(1, 0, 0)});
  rows.add_row(std::vector<Point>{Point(0, 1, 0)});
  const std::string path = test::temp_dir() + "/good.srows";
  write_rows_binary(path, rows);
  const std::string good = test::read_file(path);
  EXPECT_EQ(code_of(good.substr(0, good.size() - 1)), ErrorCode::kInputSyntax);  // truncated
  EXPECT_EQ(code_of(good + "x"), ErrorCode::kInputSyntax);                       // padded
  EXPECT_EQ(code_of("SFITROWX" + good.substr(8)), ErrorCode::kInputSyntax);      // magic
  std::string huge = good;
  const std::uint64_t lots = std::uint64_t{1} << 60;
  std::memcpy(huge.data() + 24, &lots, 8);  // claims 2^60 points: refused, not allocated
  EXPECT_EQ(code_of(huge), ErrorCode::kInputSyntax);
  std::string nan = good;
  const double bad = std::nan("");
  std::memcpy(nan.data() + 32 + 16 + 8, &bad, 8);  // y of the first point
  EXPECT_EQ(code_of(nan), ErrorCode::kInputData);
  std::string zero_row = good;
  const std::uint64_t zero = 0, three = 3;
  std::memcpy(zero_row.data() + 32 + 8, &zero, 8);
  std::memcpy(zero_row.data() + 32, &three, 8);
  EXPECT_EQ(code_of(zero_row), ErrorCode::kInputData);
  EXPECT_EQ(code_of(""), ErrorCode::kInputSyntax);
}

TEST(RowsBinary, CliPacksAndFitsTheSameSurface) {
  const std::string dir = test::temp_dir();
  const std::string hull = test::example("ship_px121_stations.rows");
  ASSERT_EQ(test::run_cli("pack '" + hull + "' -o " + dir + "/h.srows -q").exit_code, 0);
  ASSERT_EQ(test::run_cli("fit '" + hull + "' -o " + dir + "/a.json -q").exit_code, 0);
  ASSERT_EQ(test::run_cli("fit " + dir + "/h.srows -o " + dir + "/b.json -q").exit_code, 0);
  auto strip_seconds = [](std::string s) {
    const auto k = s.find("\"seconds\":");
    return s.substr(0, k) + s.substr(s.find_first_of(",}", k));
  };
  EXPECT_EQ(strip_seconds(test::read_file(dir + "/a.json")),
            strip_seconds(test::read_file(dir + "/b.json")));
  EXPECT_EQ(test::run_cli("pack '" + hull + "' -o " + dir + "/h.bin").exit_code, 2);
}

}  // namespace
}  // namespace sfit::io
