#include "fit_monitor.h"

#include <algorithm>
#include <chrono>

#include "sfit/error.h"

namespace sfit::detail {

namespace {

thread_local FitMonitor* current = nullptr;

double clock_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Phase names outlive the fit: they are the literals the method passes.
const char* stored(std::string_view name) {
  static constexpr const char* kNames[] = {"search",  "lower bound", "rows",
                                           "columns", "check",       "fold guard"};
  for (const char* n : kNames)
    if (name == n) return n;
  return "fit";
}

}  // namespace

FitMonitor::FitMonitor(const FitOptions& o)
    : progress_(o.progress),
      cancel_(o.cancel),
      owner_(std::this_thread::get_id()),
      start_(clock_seconds()),
      next_(start_ + kProgressInterval) {}

void FitMonitor::phase(std::string_view name, std::size_t total) {
  tick();
  phase_.store(stored(name), std::memory_order_relaxed);
  total_.store(total, std::memory_order_relaxed);
  done_.store(0, std::memory_order_relaxed);
  if (progress_ && std::this_thread::get_id() == owner_) report();
}

void FitMonitor::advance(std::size_t done) {
  done_.store(done, std::memory_order_relaxed);
  tick();
  if (done == total_.load(std::memory_order_relaxed) && progress_ &&
      std::this_thread::get_id() == owner_)
    report();
}

void FitMonitor::pair_tried(int nu, int nv, bool holds) {
  pairs_.fetch_add(1, std::memory_order_relaxed);
  if (holds) found(nu, nv);
  tick();
}

void FitMonitor::found(int nu, int nv) {
  const long b = best_.load(std::memory_order_relaxed);
  const long size = static_cast<long>(nu) * nv;
  if (b == 0 || size < (b >> 32) * (b & 0xffffffffL))
    best_.store(static_cast<long>(nu) << 32 | nv, std::memory_order_relaxed);
}

void FitMonitor::stop() {
  cancelled_.store(true, std::memory_order_relaxed);
  throw Error(ErrorCode::kCancelled, "the fit was cancelled");
}

void FitMonitor::poll() {
  if (clock_seconds() >= next_) report();
}

void FitMonitor::report() {
  FitProgress p;
  p.phase = phase_.load(std::memory_order_relaxed);
  p.total = total_.load(std::memory_order_relaxed);
  p.done = std::min(done_.load(std::memory_order_relaxed), p.total);
  p.pairs_tried = pairs_.load(std::memory_order_relaxed);
  const long b = best_.load(std::memory_order_relaxed);
  p.best_u = static_cast<int>(b >> 32);
  p.best_v = static_cast<int>(b & 0xffffffffL);
  const double t = clock_seconds();
  p.seconds = t - start_;
  const bool go = progress_(p);
  next_ = clock_seconds() + kProgressInterval;
  if (!go) stop();
}

FitMonitor* current_monitor() {
  return current;
}

MonitorScope::MonitorScope(FitMonitor* m) : previous_(current) {
  current = m;
}

MonitorScope::~MonitorScope() {
  current = previous_;
}

}  // namespace sfit::detail
