#include "sfit/io/csv_reader.h"

#include <gtest/gtest.h>

#include "sfit/error.h"
#include "sfit/io/rows_reader.h"
#include "test_support.h"

namespace sfit::io {
namespace {

Error parse_error(const std::string& text) {
  try {
    parse_csv(text, "in.csv");
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error for: " << text;
  return Error(ErrorCode::kInternal, "");
}

TEST(CsvReader, RowColumnLayoutGroupsConsecutiveRows) {
  const RowsFile f =
      parse_csv("row,x,y,z\n0,1,2,3\n0,4,5,6\n1,7,8,9\n1,10,11,12\n1,13,14,15\n", "a.csv");
  ASSERT_EQ(f.rows.size(), 2u);
  EXPECT_EQ(f.rows[0].size(), 2u);
  EXPECT_EQ(f.rows[1].size(), 3u);
  EXPECT_EQ(f.rows[1][2], Point(13, 14, 15));
  EXPECT_EQ(f.first_line, (std::vector<long>{2, 4}));
}

TEST(CsvReader, HeaderInAnyOrderCaseAndQuotesWithExtraColumns) {
  const RowsFile f = parse_csv(
      "\xEF\xBB\xBF\"Z\";\"Row\";\"X\";\"label\";\"Y\"\r\n3;a;1;p;2\r\n6;a;4;q;5\r\n9;b;7;r;8\r\n",
      "b.csv");
  ASSERT_EQ(f.rows.size(), 2u);
  EXPECT_EQ(f.rows[0][1], Point(4, 5, 6));
  EXPECT_EQ(f.rows[1][0], Point(7, 8, 9));
}

TEST(CsvReader, XyzLayoutWithBlankLinesBetweenRows) {
  for (const std::string head : {"", "x,y,z\n", "# comment\nx, y, z\n"}) {
    const RowsFile f = parse_csv(head + "1,2,3\n4,5,6\n\n\n7,8,9\n# note\n10,11,12\n", "c.csv");
    ASSERT_EQ(f.rows.size(), 2u) << head;
    EXPECT_EQ(f.rows[0].size(), 2u);
    EXPECT_EQ(f.rows[1].size(), 2u);
    EXPECT_EQ(f.rows[1][1], Point(10, 11, 12));
  }
  // Numbers in every form from_chars takes, and a leading '+'.
  const RowsFile g = parse_csv("-1.5e3,+2,.25\n", "d.csv");
  EXPECT_EQ(g.rows[0][0], Point(-1500, 2, 0.25));
}

TEST(CsvReader, ErrorsNameFileLineAndColumn) {
  Error e = parse_error("x,y,z\n1,2,3\n1,zz,3\n");
  EXPECT_EQ(e.code(), ErrorCode::kInputSyntax);
  EXPECT_EQ(e.place().file, "in.csv");
  EXPECT_EQ(e.place().line, 3);
  EXPECT_EQ(e.place().column, 3);
  EXPECT_NE(std::string(e.what()).find("'zz' is not a number"), std::string::npos);

  e = parse_error("1,2,3\n1,2\n");
  EXPECT_EQ(e.code(), ErrorCode::kInputSyntax);
  EXPECT_EQ(e.place().line, 2);
  EXPECT_NE(std::string(e.what()).find("expected 3 fields (x,y,z), found 2"), std::string::npos);

  e = parse_error("row,x,y,z\n0,1,2,3\n1,1,2,3\n0,1,2,3\n");
  EXPECT_EQ(e.code(), ErrorCode::kInputSyntax);
  EXPECT_EQ(e.place().line, 4);
  EXPECT_EQ(e.place().column, 1);
  EXPECT_NE(std::string(e.what()).find("row '0' already ended at line 2"), std::string::npos);

  e = parse_error("row,a,b,c\n0,1,2,3\n");
  EXPECT_EQ(e.code(), ErrorCode::kInputSyntax);
  EXPECT_EQ(e.place().line, 1);
  EXPECT_NE(std::string(e.what()).find("no 'x' column"), std::string::npos);

  e = parse_error("x,y,z\n1,nan,3\n");
  EXPECT_EQ(e.code(), ErrorCode::kInputData);
  EXPECT_EQ(e.place().column, 3);

  e = parse_error("x,y,z\n1,1e999,3\n");
  EXPECT_EQ(e.code(), ErrorCode::kInputData);

  e = parse_error("x,y,z\n1,,3\n");
  EXPECT_EQ(e.code(), ErrorCode::kInputSyntax);
  EXPECT_NE(std::string(e.what()).find("empty field"), std::string::npos);

  e = parse_error("row,x,y,z\n");
  EXPECT_EQ(e.code(), ErrorCode::kInputData);
  EXPECT_NE(std::string(e.what()).find("no points"), std::string::npos);

  // The one-line form the CLI prints.
  e = parse_error("x,y,z\n1,2,3\n1,2,3,4\n");
  EXPECT_EQ(format_error_line(e.place(), e.message()).rfind("in.csv:3:7: ", 0), 0u)
      << format_error_line(e.place(), e.message());
}

TEST(CsvReader, FilesMissingOrFolders) {
  try {
    read_csv("/nonexistent/p.csv");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputUnreadable);
  }
  try {
    read_csv(test::temp_dir());
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputUnreadable);
  }
}

// The same points as the bundled .rows file, written as CSV both ways, read to the same rows.
TEST(CsvReader, ShipStationsAsCsvEqualTheRowsFile) {
  const Rows rows = test::load_rows(test::example("ship_px121_stations.rows"));
  std::string by_row = "row,x,y,z\n", blank;
  char buf[160];
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (const Point& p : rows[j]) {
      std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g", p.x(), p.y(), p.z());
      by_row += std::to_string(j) + "," + buf + "\n";
      blank += std::string(buf) + "\n";
    }
    blank += "\n";
  }
  const std::string dir = test::temp_dir();
  test::write_file(dir + "/a.csv", by_row);
  test::write_file(dir + "/b.csv", blank);
  for (const char* name : {"/a.csv", "/b.csv"}) {
    const RowsFile f = read_csv(dir + name);
    ASSERT_EQ(f.rows.size(), rows.size());
    EXPECT_EQ(f.rows.offsets(), rows.offsets());
    EXPECT_EQ(f.rows.points(), rows.points());
  }
}

// A number field means the same in both readers: a leading '+', underflow to 0 or a subnormal
// (as strtod), overflow, NaN and words refused with the same message and code.
TEST(CsvReader, NumbersReadAsTheRowsReaderReadsThem) {
  const RowsFile c = parse_csv("x,y,z\n+1,1e-400,4.9e-324\n2,3,4\n", "in.csv");
  const RowsFile r = parse_rows("+1 1e-400 4.9e-324\n2 3 4\n", "in.rows");
  ASSERT_EQ(c.rows.total_points(), 2u);
  EXPECT_EQ(c.rows.points(), r.rows.points());
  EXPECT_EQ(c.rows[0][0].y(), 0.0);
  EXPECT_GT(c.rows[0][0].z(), 0.0);  // the smallest subnormal, not 0
  for (const char* bad : {"1e400", "-1e999", "nan", "inf", "1.2.3", "+", "0x1p3"}) {
    const Error ec = parse_error(std::string("x,y,z\n1,") + bad + ",3\n");
    Error er(ErrorCode::kInternal, "");
    try {
      parse_rows(std::string("1 ") + bad + " 3\n", "in.rows");
      ADD_FAILURE() << "no .rows error for " << bad;
    } catch (const Error& e) {
      er = e;
    }
    EXPECT_EQ(ec.code(), er.code()) << bad;
    EXPECT_EQ(ec.message(), er.message()) << bad;
  }
}

}  // namespace
}  // namespace sfit::io
