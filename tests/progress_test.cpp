// Progress and cancel of a fit (sfit/progress.h): FitOptions::progress sees every phase and
// changes nothing; returning false, or FitOptions::cancel, stops the fit with kCancelled.
#include "sfit/progress.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "sfit/error.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit {
namespace {

using test::expect_same_surface;

Rows wavy(int rows = 60, int points = 80) {
  return test::sample_rows(
      [](double s, double t) {
        return Point(10 * s, 8 * t, std::sin(7 * s) * std::cos(5 * t) + 0.3 * std::sin(19 * s * t));
      },
      std::vector<int>(rows, points));
}

FitOptions options(int threads = 2) {
  FitOptions o;
  o.tolerance = Point::Constant(1e-3);
  o.threads = threads;
  return o;
}

struct Call {
  std::string phase;
  FitProgress p;
};

TEST(Progress, ReportsEveryPhaseAndChangesNothing) {
  const Rows rows = wavy();
  for (FitMethod method : {FitMethod::kSurface, FitMethod::kSfit01}) {
    std::vector<Call> calls;
    FitOptions o = options();
    o.method = method;
    o.progress = [&](const FitProgress& p) {
      calls.push_back({std::string(p.phase), p});
      return true;
    };
    const FitResult with = fit_surface(rows, o);
    o.progress = {};
    const FitResult without = fit_surface(rows, o);
    expect_same_surface(with, without);

    std::set<std::string> phases;
    for (const Call& c : calls) phases.insert(c.phase);
    EXPECT_TRUE(phases.count("rows") && phases.count("columns") && phases.count("check"))
        << to_string(method);
    EXPECT_EQ(phases.count("search"), method == FitMethod::kSurface ? 1u : 0u);
    double seconds = 0;
    long pairs = 0;
    for (const Call& c : calls) {
      EXPECT_LE(c.p.done, c.p.total) << c.phase;
      EXPECT_GE(c.p.seconds, seconds) << c.phase;
      EXPECT_GE(c.p.pairs_tried, pairs) << c.phase;
      seconds = c.p.seconds;
      pairs = c.p.pairs_tried;
    }
    // Each phase reports its end (done == total) on the fit's thread.
    bool rows_ended = false;
    for (const Call& c : calls)
      rows_ended = rows_ended || (c.phase == "rows" && c.p.done == c.p.total);
    EXPECT_TRUE(rows_ended);
    if (method == FitMethod::kSurface) {
      const FitProgress& last = calls.back().p;
      EXPECT_GT(last.pairs_tried, 0);
      EXPECT_LE(last.pairs_tried, with.report.pairs_tried);
      // The best so far is a pair that held: never more control points than the result.
      ASSERT_GT(last.best_u, 0);
      EXPECT_LE(static_cast<long>(last.best_u) * last.best_v,
                static_cast<long>(with.surface.count_u) * with.surface.count_v);
    } else {
      EXPECT_EQ(calls.back().p.pairs_tried, 0);
    }
  }
}

TEST(Progress, FalseStopsTheFitWithItsOwnCode) {
  const Rows rows = wavy();
  for (const char* stop_at : {"search", "rows", "columns", "check"}) {
    int calls_after = 0;
    bool stopped = false;
    FitOptions o = options();
    if (std::string(stop_at) != "search") o.method = FitMethod::kSfit01;
    o.progress = [&](const FitProgress& p) {
      if (stopped) ++calls_after;
      if (p.phase == stop_at) stopped = true;
      return !stopped;
    };
    try {
      fit_surface(rows, o);
      ADD_FAILURE() << "the fit ran to its end after progress returned false at " << stop_at;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kCancelled) << e.what();
      EXPECT_EQ(e.exit_code(), 9);
      EXPECT_STREQ(to_string(e.code()), "cancelled");
    }
    EXPECT_TRUE(stopped) << stop_at;
    EXPECT_EQ(calls_after, 0) << stop_at;
  }
}

TEST(Progress, CancelFlagStopsTheFitOnAnyThreadCount) {
  const Rows rows = wavy();
  for (int threads : {1, 4}) {
    std::atomic<bool> cancel{true};
    FitOptions o = options(threads);
    o.cancel = &cancel;
    EXPECT_THROW(
        {
          try {
            fit_surface(rows, o);
          } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kCancelled);
            throw;
          }
        },
        Error);
    // Set by another thread while the search runs (as a signal handler or a UI would).
    cancel = false;
    std::atomic<bool> searching{false};
    o.progress = [&](const FitProgress& p) {
      if (p.phase == "search") searching = true;
      return true;
    };
    std::thread setter([&] {
      while (!searching) std::this_thread::yield();
      cancel = true;
    });
    bool cancelled = false;
    try {
      fit_surface(rows, o);
    } catch (const Error& e) {
      cancelled = e.code() == ErrorCode::kCancelled;
    }
    if (!searching) searching = true;  // a fit that never searched: let the thread end
    setter.join();
    EXPECT_TRUE(cancelled) << threads << " threads";
  }
}

TEST(Progress, SameBitsOnOneAndFourThreadsWithProgressAndCancel) {
  const Rows rows = wavy(40, 300);
  std::atomic<bool> never{false};
  std::vector<FitResult> fits;
  for (int threads : {1, 4}) {
    for (bool watched : {false, true}) {
      FitOptions o = options(threads);
      if (watched) {
        o.progress = [](const FitProgress&) { return true; };
        o.cancel = &never;
      }
      fits.push_back(fit_surface(rows, o));
    }
  }
  for (std::size_t k = 1; k < fits.size(); ++k) expect_same_surface(fits[0], fits[k]);
}

}  // namespace
}  // namespace sfit
