// Saving edited rows (src/server/save_file.*, rows_text.*): the weight column travels, the
// head of the file (byte-order mark, comments, CRLF) stays, INPUT.bak is written once and never
// replaced, a symbolic link is written through, the mode stays, read-only files and files with
// other hard links are refused with nothing written.
#include "save_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "sfit/error.h"
#include "sfit/io/rows_reader.h"
#include "test_support.h"

namespace sfit::server {
namespace {

namespace fs = std::filesystem;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The rows of `text` moved: every x + 1 (weights as read).
Rows moved(const std::string& path) {
  const Rows in = io::read_rows(path).rows;
  Rows out;
  for (std::size_t j = 0; j < in.size(); ++j) {
    for (const Point& p : in[j]) out.push_point(Point(p.x() + 1, p.y(), p.z()));
    out.end_row();
  }
  if (in.weighted()) out.set_weights(in.weights());
  return out;
}

const std::string kWeighted =
    "# name: weighted\n# rows are OPEN curves\n"
    "0 0 0 1\n1 0 0.5 2.5\n2 0 0 0.125\n\n0 1 0 3\n1 1 0.25 1e-3\n2 1 0 7\n";

// Saves the rows `rows` to `path` as the editor does and reads them back.
std::string message_of(const std::string& path, const Rows& rows) {
  try {
    save_rows(path, rows);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kOutputWrite);
    return e.what();
  }
  return "(saved)";
}

TEST(SaveRows, WeightsAreSavedAndReadBackExactly) {
  const std::string path = test::temp_dir() + "/w.rows";
  spit(path, kWeighted);
  const Rows rows = moved(path);
  const SaveResult r = save_rows(path, rows);
  EXPECT_EQ(r.target, path);
  EXPECT_TRUE(r.backup_written);
  const Rows back = io::read_rows(path).rows;
  ASSERT_TRUE(back.weighted());
  EXPECT_EQ(back.weights(), (std::vector<double>{1, 2.5, 0.125, 3, 1e-3, 7}));
  EXPECT_EQ(back.points(), rows.points());
  EXPECT_EQ(back.offsets(), rows.offsets());
  EXPECT_EQ(slurp(path),
            "# name: weighted\n# rows are OPEN curves\n"
            "1 0 0 1\n2 0 0.5 2.5\n3 0 0 0.125\n\n1 1 0 3\n2 1 0.25 0.001\n3 1 0 7\n");
}

TEST(SaveRows, ByteOrderMarkCommentsAndCrlfStay) {
  const std::string path = test::temp_dir() + "/bom.rows";
  spit(path,
       "\xEF\xBB\xBF# name: bom\r\n# units: mm\r\n\r\n0 0 0\r\n1 0 1\r\n\r\n0 1 0\r\n1 1 1\r\n");
  save_rows(path, moved(path));
  EXPECT_EQ(
      slurp(path),
      "\xEF\xBB\xBF# name: bom\r\n# units: mm\r\n\r\n1 0 0\r\n2 0 1\r\n\r\n1 1 0\r\n2 1 1\r\n");
  EXPECT_EQ(io::read_rows(path).rows.total_points(), 4u);
}

TEST(SaveRows, TheBackupIsWrittenOnceAndNeverReplaced) {
  const std::string path = test::temp_dir() + "/b.rows";
  spit(path, kWeighted);
  // Three "sessions" of two saves each: the backup stays the original.
  for (int session = 0; session < 3; ++session)
    for (int save = 0; save < 2; ++save) {
      const SaveResult r = save_rows(path, moved(path));
      EXPECT_EQ(r.backup, path + ".bak");
      EXPECT_EQ(r.backup_written, session == 0 && save == 0);
      EXPECT_EQ(slurp(path + ".bak"), kWeighted);
    }
  EXPECT_EQ(io::read_rows(path).rows.points()[0].x(), 6.0);  // moved six times
}

TEST(SaveRows, ThroughASymbolicLinkTheTargetIsWrittenAndTheLinkStays) {
  const std::string dir = test::temp_dir();
  fs::create_directory(dir + "/data");
  const std::string target = dir + "/data/real.rows", link = dir + "/link.rows";
  spit(target, kWeighted);
  ASSERT_EQ(::chmod(target.c_str(), 0640), 0);
  fs::create_symlink("data/real.rows", link);
  const SaveResult r = save_rows(link, moved(link));
  EXPECT_EQ(r.target, fs::canonical(target).string());
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(fs::read_symlink(link), "data/real.rows");
  EXPECT_EQ(io::read_rows(target).rows.points()[0].x(), 1.0);
  EXPECT_EQ(slurp(link + ".bak"), kWeighted);
  struct stat st {};
  ASSERT_EQ(::stat(target.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u) << "the mode stays";
  EXPECT_EQ(st.st_nlink, 1u);
}

TEST(SaveRows, ADanglingLinkIsRefused) {
  const std::string dir = test::temp_dir();
  spit(dir + "/gone.rows", kWeighted);
  const Rows rows = moved(dir + "/gone.rows");
  fs::create_symlink("nowhere.rows", dir + "/link.rows");
  EXPECT_EQ(message_of(dir + "/link.rows", rows),
            dir +
                "/link.rows: cannot save: its link leads nowhere: No such file or directory; "
                "nothing written");
  EXPECT_FALSE(fs::exists(dir + "/link.rows.bak"));
}

TEST(SaveRows, AReadOnlyInputIsRefusedAndNothingWritten) {
  const std::string dir = test::temp_dir(), path = dir + "/ro.rows";
  spit(path, kWeighted);
  const Rows rows = moved(path);
  ASSERT_EQ(::chmod(path.c_str(), 0444), 0);
  EXPECT_EQ(message_of(path, rows),
            path + ": cannot save: '" + path + "' is read-only (mode 0444); nothing written");
  EXPECT_EQ(slurp(path), kWeighted);
  EXPECT_FALSE(fs::exists(path + ".bak"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1)
      << "no temporary file left";
}

TEST(SaveRows, AFileWithOtherHardLinksIsRefusedAndNothingWritten) {
  const std::string dir = test::temp_dir(), path = dir + "/h.rows";
  spit(path, kWeighted);
  ASSERT_EQ(::link(path.c_str(), (dir + "/other.rows").c_str()), 0);
  EXPECT_EQ(message_of(path, moved(path)),
            path + ": cannot save: '" + path +
                "' has 2 hard links and saving (a new file renamed over it) would break them; "
                "copy it to a file of its own to edit it; nothing written");
  EXPECT_EQ(slurp(path), kWeighted);
  EXPECT_EQ(slurp(dir + "/other.rows"), kWeighted);
  EXPECT_FALSE(fs::exists(path + ".bak"));
}

}  // namespace
}  // namespace sfit::server
