// The editor's full searches (src/server): a file with no surface within its T opens with the
// best surface found (best_effort.h) and an edit that fits it brings the search back; a full
// search at rest is cancelled by a drag step (search_watch.h) and leaves the drag as it was;
// its progress is reported.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "search_watch.h"
#include "session.h"
#include "sfit/error.h"
#include "test_support.h"

namespace sfit::server {
namespace {

TEST(BestEffort, AFileWithNoSurfaceWithinTOpensAndAnEditThatFitsBringsTheSearchBack) {
  Rows rows =
      test::load_rows(test::example("../tests/bad_input/degree20_interpolation_not_met.rows"));
  FitOptions o;
  o.degree_u = o.degree_v = 20;
  EXPECT_THROW(fit_surface(rows, o), Error);  // sfit fit refuses it (exit 7)
  Session s(rows, o);
  EXPECT_NE(s.best_effort().find("re-representation cannot hold the tolerance"), std::string::npos)
      << s.best_effort();
  EXPECT_NE(s.best_effort().find("shown: "), std::string::npos) << s.best_effort();
  EXPECT_EQ(s.options().degree_u, 20);  // the options as asked
  EXPECT_EQ(s.rows().total_points(), rows.total_points());
  FitOptions fixed = o;
  fixed.degree_u = fixed.degree_v = 3;
  s.set_options(fixed);
  EXPECT_TRUE(s.best_effort().empty());
  EXPECT_TRUE(s.result().report.within_tolerance);
  const FitResult direct = fit_surface(rows, fixed);
  EXPECT_EQ(s.result().report.count_u, direct.report.count_u);
  EXPECT_EQ(s.result().report.count_v, direct.report.count_v);
  // A point moved while the best effort is shown: the search is tried again (and fails again).
  ASSERT_TRUE(s.undo());
  EXPECT_FALSE(s.best_effort().empty());
  const Point p = s.rows()[1][3];
  s.move(1, 3, p + Point(0, 0, 1), MovePhase::kOnce);
  EXPECT_FALSE(s.best_effort().empty());
  EXPECT_EQ(s.rows()[1][3], p + Point(0, 0, 1));
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(s.rows()[1][3], p);
}

TEST(SearchWatch, ADragStepCancelsTheSearchAtRestAndTheDragGoesOn) {
  Rows rows = test::load_rows(test::example("ship_px121_stations.rows"));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  SearchWatch w;
  Session s(std::move(rows), w.watched(o));
  const nlohmann::json first = w.progress();
  EXPECT_FALSE(first["running"].get<bool>());
  EXPECT_TRUE(first.contains("phase")) << first.dump();  // the first fit reported
  EXPECT_FALSE(w.cancel()) << "nothing cancellable runs";
  const Point p = s.rows()[5][4], to = p + Point(0, 1, 1);
  const std::size_t undo = s.undo_depth();
  {
    const SearchWatch::Scope scope(w, false);
    s.move(5, 4, to, MovePhase::kDrag);
  }
  {
    const SearchWatch::Scope scope(w, true);
    EXPECT_TRUE(w.cancel());  // a drag step came while the rest's search would run
    try {
      s.move(5, 4, to + Point(0, 0.5, 0), MovePhase::kRest);
      ADD_FAILURE() << "the rest's search was not cancelled";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kCancelled);
    }
    w.dropped("the test's search");
  }
  EXPECT_EQ(w.progress()["dropped"].get<long>(), 1);
  EXPECT_TRUE(s.dragging());
  EXPECT_FALSE(s.final());
  EXPECT_EQ(s.rows()[5][4], p) << "the full fit is as before the drag";
  EXPECT_EQ(s.shown_rows()[5][4], to) << "the quick state where the drag was";
  {
    const SearchWatch::Scope scope(w, false);  // the cancel flag cleared
    s.move(5, 4, to, MovePhase::kEnd);
  }
  EXPECT_FALSE(s.dragging());
  EXPECT_TRUE(s.final());
  EXPECT_EQ(s.rows()[5][4], to);
  EXPECT_TRUE(s.result().report.within_tolerance);
  EXPECT_EQ(s.undo_depth(), undo + 1);
  EXPECT_FALSE(w.progress()["running"].get<bool>());
}

}  // namespace
}  // namespace sfit::server
