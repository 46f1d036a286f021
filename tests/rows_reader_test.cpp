#include "sfit/io/rows_reader.h"

#include <gtest/gtest.h>

#include "sfit/error.h"
#include "test_support.h"

namespace sfit::io {
namespace {

ErrorCode code_of(const std::string& text, Place* where = nullptr) {
  try {
    parse_rows(text, "in.rows");
  } catch (const Error& e) {
    if (where) *where = e.place();
    return e.code();
  }
  return ErrorCode::kInternal;  // nothing thrown
}

TEST(RowsReader, RowsCommentsAndSeparators) {
  const auto f = parse_rows(
      "# header\n1 2 3\n4 5 6   # trailing comment\n\n\n\n7 8 9\n# a comment line does not "
      "split\n10 11 12\n\n",
      "in.rows");
  ASSERT_EQ(f.rows.size(), 2u);
  EXPECT_EQ(f.rows[0].size(), 2u);
  EXPECT_EQ(f.rows[1].size(), 2u);
  EXPECT_EQ(f.rows[1][1], Point(10, 11, 12));
  EXPECT_EQ(f.first_line, (std::vector<long>{2, 7}));
}

TEST(RowsReader, AcceptsCrlfBomTabsCommasAndPlusSigns) {
  const auto f = parse_rows(
      "\xEF\xBB\xBF"
      "1,2,3\r\n4\t5\t6\r\n\r\n+7 -8e1 .5\r\n",
      "in.rows");
  ASSERT_EQ(f.rows.size(), 2u);
  EXPECT_EQ(f.rows[0][1], Point(4, 5, 6));
  EXPECT_EQ(f.rows[1][0], Point(7, -80, 0.5));
}

TEST(RowsReader, ReadsTheLastLineWithoutNewline) {
  const auto f = parse_rows("1 2 3\n4 5 6", "in.rows");
  EXPECT_EQ(f.rows[0].size(), 2u);
}

TEST(RowsReader, ErrorsNameLineAndColumn) {
  Place p;
  EXPECT_EQ(code_of("1 2 3\n4 x 6\n", &p), ErrorCode::kInputSyntax);
  EXPECT_EQ(p.line, 2);
  EXPECT_EQ(p.column, 3);
  EXPECT_EQ(code_of("1 2 3\n4 5\n", &p), ErrorCode::kInputSyntax);
  EXPECT_EQ(p.line, 2);
  EXPECT_EQ(code_of("1 2 3 4 5\n", &p), ErrorCode::kInputSyntax);  // a 4th is a weight
  EXPECT_EQ(p.column, 9);
  EXPECT_EQ(code_of("1 nan 3\n", &p), ErrorCode::kInputData);
  EXPECT_EQ(p.column, 3);
  EXPECT_EQ(code_of("1 2 inf\n"), ErrorCode::kInputData);
  EXPECT_EQ(code_of("1 2 1e400\n"), ErrorCode::kInputData);
  EXPECT_EQ(code_of(""), ErrorCode::kInputData);
  EXPECT_EQ(code_of("# only comments\n\n"), ErrorCode::kInputData);
  EXPECT_EQ(code_of(std::string("1 2 3\n") + std::string(2 << 20, '1') + "\n"),
            ErrorCode::kInputSyntax);
}

TEST(RowsReader, MessagesAreOneLineWithPlace) {
  try {
    parse_rows("1 2 3\n4 5 six\n", "data/x.rows");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "data/x.rows:2:5: row 0, point 1: 'six' is not a number");
  }
}

TEST(RowsReader, FileAndMissingFile) {
  const std::string dir = test::temp_dir();
  test::write_file(dir + "/a.rows", "0 0 0\n1 0 0\n\n0 1 0\n1 1 1\n");
  const auto f = read_rows(dir + "/a.rows");
  EXPECT_EQ(f.rows.total_points(), 4u);
  try {
    read_rows(dir + "/missing.rows");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputUnreadable);
    EXPECT_EQ(e.place().file, dir + "/missing.rows");
  }
  try {
    read_rows(dir);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputUnreadable);
  }
}

TEST(RowsReader, SharedDataSetsReadWithTheirDocumentedCounts) {
  // Row and point counts as the files' headers state them.
  struct Expect {
    const char* file;
    std::size_t rows, points;
  };
  for (const Expect& e :
       {Expect{"ship_px121_stations.rows", 11, 90}, Expect{"iea3p4mw_blade_ragged9.rows", 9, 1836},
        Expect{"d150_wing.rows", 4, 152}, Expect{"iea15mw_blade_af50.rows", 50, 9992},
        Expect{"topobathy.rows", 91, 10920}}) {
    const auto f = read_rows(test::example(e.file));
    EXPECT_EQ(f.rows.size(), e.rows) << e.file;
    EXPECT_EQ(f.rows.total_points(), e.points) << e.file;
  }
}

}  // namespace
}  // namespace sfit::io
