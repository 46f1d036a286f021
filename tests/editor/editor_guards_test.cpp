// The editor server's guards (src/server): the lock that makes a second editor of a file
// read-only, the hold of the surface's counts and rule, and the watch that ends a drag whose
// page went away at the full fit.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "drag_watch.h"
#include "file_lock.h"
#include "hold.h"
#include "session.h"
#include "sfit/error.h"
#include "test_support.h"

namespace sfit::server {
namespace {

namespace fs = std::filesystem;

std::string scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("sfit-guards-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return (dir / name).string();
}

TEST(FileLock, ASecondEditorOfTheFileIsReadOnlyUntilTheFirstEnds) {
  const std::string input = scratch("a.rows");
  {
    FileLock first(input);
    EXPECT_TRUE(first.writable());
    EXPECT_TRUE(first.why().empty());
    EXPECT_TRUE(fs::exists(input + ".sfit-lock"));
    FileLock second(input);
    EXPECT_FALSE(second.writable());
    EXPECT_NE(second.why().find("process " + std::to_string(::getpid())), std::string::npos)
        << second.why();
  }  // the first ends: its lock goes, the second's destructor left it alone
  EXPECT_FALSE(fs::exists(input + ".sfit-lock"));
  FileLock third(input);
  EXPECT_TRUE(third.writable());
}

TEST(FileLock, AStaleLockIsTakenOver) {
  const std::string input = scratch("b.rows");
  {
    std::ofstream(input + ".sfit-lock") << 999999999 << "\n";  // no such process
  }
  FileLock lock(input);
  EXPECT_TRUE(lock.writable()) << lock.why();
  std::ifstream in(input + ".sfit-lock");
  long pid = 0;
  in >> pid;
  EXPECT_EQ(pid, static_cast<long>(::getpid()));
}

Session ship_session(double relative = 1e-3) {
  Rows rows = test::load_rows(test::example("ship_px121_stations.rows"));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, relative);
  return Session(std::move(rows), o);
}

TEST(Hold, KeepsTheCountsAndTheRuleThroughEditsUntilReleased) {
  Session s = ship_session();
  const FitReport r0 = s.result().report;
  s.set_options(options_with_hold(nlohmann::json{{"hold", true}}, s));
  EXPECT_TRUE(held(s.options()));
  const Point p = s.rows()[5][4];
  const double far = 0.05 * (s.rows()[5][5] - s.rows()[5][3]).norm() + 2.0;
  const Surface& s0 = s.result().surface;
  const std::vector<double> knots_u = s0.full_knots_u(), knots_v = s0.full_knots_v();
  for (MovePhase ph : {MovePhase::kDrag, MovePhase::kRest, MovePhase::kEnd}) {
    s.move(5, 4, p + Point(0, far, far), ph);
    EXPECT_EQ(s.shown().report.count_u, r0.count_u);
    EXPECT_EQ(s.shown().report.count_v, r0.count_v);
    EXPECT_EQ(s.shown().report.parametrization, r0.parametrization);
    EXPECT_EQ(s.shown().surface.full_knots_u(), knots_u);  // the knots too
    EXPECT_EQ(s.shown().surface.full_knots_v(), knots_v);
  }
  // Another option keeps the hold; the search's answer leaves the session alone.
  s.set_options(options_with_hold(nlohmann::json{{"search", "linear"}}, s));
  EXPECT_TRUE(held(s.options()));
  const long v = s.version();
  const nlohmann::json answer = search_without_hold(nlohmann::json{{"parameters", "auto"}}, s);
  EXPECT_EQ(s.version(), v);
  EXPECT_EQ(answer["held"][0].get<int>(), r0.count_u);
  EXPECT_TRUE(answer["within"].get<bool>());
  // Released: the full search, within T, as a fit without the hold would give.
  s.set_options(options_with_hold(nlohmann::json{{"hold", false}, {"parameters", "auto"}}, s));
  EXPECT_FALSE(held(s.options()));
  EXPECT_TRUE(s.result().report.within_tolerance);
  EXPECT_EQ(s.result().report.count_u, answer["counts"][0].get<int>());
  EXPECT_EQ(s.result().report.count_v, answer["counts"][1].get<int>());
  EXPECT_THROW(options_with_hold(nlohmann::json{{"hold", 1}}, s), Error);
}

TEST(DragWatch, EndsAQuickDragWhoseClientWentAwayAtTheFullFit) {
  Session s = ship_session();
  std::mutex m;
  const std::size_t undo = s.undo_depth();
  DragWatch watch(m, s, std::chrono::milliseconds(200));
  {
    std::lock_guard<std::mutex> lock(m);
    s.move(5, 4, s.rows()[5][4] + Point(0, 1, 1), MovePhase::kDrag);
    watch.touch();
    EXPECT_TRUE(s.dragging());
    EXPECT_FALSE(s.final());
  }
  for (int k = 0; k < 100 && watch.ended() == 0; ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::lock_guard<std::mutex> lock(m);
  EXPECT_EQ(watch.ended(), 1);
  EXPECT_FALSE(s.dragging());
  EXPECT_TRUE(s.final());
  EXPECT_EQ(s.undo_depth(), undo + 1);
  EXPECT_TRUE(s.result().report.within_tolerance);
}

TEST(DragWatch, LeavesALiveDragAlone) {
  Session s = ship_session();
  std::mutex m;
  DragWatch watch(m, s, std::chrono::milliseconds(300));
  const Point p = s.rows()[5][4];
  for (int k = 1; k <= 10; ++k) {
    {
      std::lock_guard<std::mutex> lock(m);
      s.move(5, 4, p + Point(0, 0.1 * k, 0), MovePhase::kDrag);
      watch.touch();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
  }
  std::lock_guard<std::mutex> lock(m);
  EXPECT_EQ(watch.ended(), 0);
  EXPECT_TRUE(s.dragging());
  s.finish_drag();
}

}  // namespace
}  // namespace sfit::server
