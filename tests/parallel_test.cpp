// The deterministic parallel loop and its persistent pool (src/core/fit/parallel.h).
#include "parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <vector>

namespace sfit::detail {
namespace {

TEST(Parallel, EveryIndexOnceOnAnyThreadCount) {
  for (int threads : {1, 2, 3, 8}) {
    std::vector<int> hits(1000, 0);
    parallel_for(hits.size(), threads, [&](std::size_t i) { hits[i] += 1; });
    EXPECT_EQ(std::accumulate(hits.begin(), hits.end(), 0), 1000) << threads;
    EXPECT_EQ(*std::min_element(hits.begin(), hits.end()), 1) << threads;
  }
}

thread_local long indices_on_this_thread = 0;

TEST(Parallel, HelpersArePersistentThreads) {
  // The pool's threads outlive a loop, so their per-thread caches stay warm: a helper's
  // thread_local state from the first loop is still there in the second (a thread made per
  // loop would start the second at 0).
  const auto caller = std::this_thread::get_id();
  std::mutex m;
  bool gave_up = false;
  auto loop = [&](std::vector<long>& helper_counts_seen) {
    parallel_for(64, 2, [&](std::size_t) {
      const long before = indices_on_this_thread++;
      if (std::this_thread::get_id() != caller) {
        std::lock_guard<std::mutex> lock(m);
        helper_counts_seen.push_back(before);
        return;
      }
      // The calling thread waits (up to 2 s) until a helper has taken an index too, so the
      // helper's part does not depend on how fast it wakes.
      for (int wait = 0; wait < 2000 && !gave_up; ++wait) {
        {
          std::lock_guard<std::mutex> lock(m);
          if (!helper_counts_seen.empty()) return;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      gave_up = true;  // no helper at all: wait once, not per index
    });
  };
  std::vector<long> first, second;
  loop(first);
  loop(second);
  ASSERT_FALSE(first.empty());
  ASSERT_FALSE(second.empty());
  EXPECT_GT(*std::min_element(second.begin(), second.end()), 0);
}

TEST(Parallel, NestedLoopsRunAndExceptionsReachTheCaller) {
  std::vector<long> sums(40, 0);
  parallel_for(sums.size(), 2, [&](std::size_t i) {
    std::vector<long> inner(100, 0);
    parallel_for(inner.size(), 2, [&](std::size_t k) { inner[k] = static_cast<long>(i * k); });
    sums[i] = std::accumulate(inner.begin(), inner.end(), 0L);
  });
  for (std::size_t i = 0; i < sums.size(); ++i) EXPECT_EQ(sums[i], static_cast<long>(i) * 4950);
  EXPECT_THROW(parallel_for(100, 2,
                            [](std::size_t i) {
                              if (i == 57) throw std::runtime_error("57");
                            }),
               std::runtime_error);
  // The pool still works after an exception.
  std::vector<int> hits(100, 0);
  parallel_for(hits.size(), 2, [&](std::size_t i) { hits[i] = 1; });
  EXPECT_EQ(std::accumulate(hits.begin(), hits.end(), 0), 100);
}

}  // namespace
}  // namespace sfit::detail
