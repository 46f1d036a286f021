// A minimal deterministic parallel loop: each index is computed by exactly one thread and
// writes only its own result, so the output does not depend on the thread count.
//
// The threads are a persistent pool (parallel.cpp), not made per call: the per-thread caches
// of factorisations (curve_fit.cpp, rerepresent.cpp) then stay warm from one stage to the
// next. With threads made per call every stage started cold, and the exact-maximum pass on a
// 10^6-point grid at 1e-3 took 2x longer on 2 threads than on 1.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "fit_monitor.h"
#include "sfit/fit_limits.h"

namespace sfit::detail {

inline int resolve_threads(int requested) {
  // Never more than the library's limit (sfit/fit_limits.h): results do not depend on it.
  if (requested > 0) return std::min(requested, kMaxThreads);
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

/// Runs `work` on the calling thread and on `helpers` pool threads at once and returns when
/// all have returned. False (nothing run) when the pool is busy (another thread's parallel
/// loop) or this is a pool thread: the caller then runs the work itself.
bool run_on_pool(int helpers, const std::function<void()>& work);

/// Calls f(i) for i in [0, n), on up to `threads` threads (dynamic chunks). The first
/// exception thrown by any f is rethrown here after all threads stop. The fit's monitor
/// (fit_monitor.h) goes with the work to every thread, and ticks before each f(i): a
/// cancelled fit stops every thread at its next index.
template <class F>
void parallel_for(std::size_t n, int threads, F&& f) {
  threads = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(threads), n));
  FitMonitor* const monitor = current_monitor();
  if (threads <= 1) {
    for (std::size_t i = 0; i < n; ++i) {
      if (monitor) monitor->tick();
      f(i);
    }
    return;
  }
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  const std::size_t chunk = std::max<std::size_t>(1, n / (static_cast<std::size_t>(threads) * 8));
  const std::function<void()> worker = [&] {
    const MonitorScope scope(monitor);
    while (true) {
      const std::size_t begin = next.fetch_add(chunk);
      if (begin >= n) return;
      const std::size_t end = std::min(n, begin + chunk);
      try {
        for (std::size_t i = begin; i < end; ++i) {
          if (monitor) monitor->tick();
          f(i);
        }
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next.store(n);
        return;
      }
    }
  };
  if (!run_on_pool(threads - 1, worker)) worker();
  if (error) std::rethrow_exception(error);
}

}  // namespace sfit::detail
