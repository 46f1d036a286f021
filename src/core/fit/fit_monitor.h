// The progress and cancel of the fit running on this thread (FitOptions::progress, ::cancel;
// sfit/progress.h). Private. fit_surface() installs one FitMonitor for the whole fit;
// parallel_for() hands it to its pool threads; long loops call tick(), which costs an
// atomic load (and, on the fit's own thread, a clock read) until the fit is cancelled.
#pragma once

#include <atomic>
#include <cstddef>
#include <mutex>
#include <string_view>
#include <thread>

#include "sfit/surface_fit.h"

namespace sfit::detail {

class FitMonitor {
 public:
  /// Nothing to watch: no monitor is needed (fit_surface() installs none).
  static bool wanted(const FitOptions& o) { return o.progress || o.cancel; }

  explicit FitMonitor(const FitOptions& o);

  /// A new phase of `total` items: reported at once (not rate-limited).
  void phase(std::string_view name, std::size_t total);
  /// `done` items of the phase; reported at once when it ends the phase (done == total).
  void advance(std::size_t done);
  /// One more item done (any thread).
  void step() { done_.fetch_add(1, std::memory_order_relaxed); }
  /// One more pair solved by the surface search; `holds`: it held (the best is kept).
  void pair_tried(int nu, int nv, bool holds);
  /// A pair that holds (kept as the best where it has fewer nu x nv).
  void found(int nu, int nv);
  /// Throws Error kCancelled once the fit is cancelled; calls the progress function on the
  /// fit's own thread every kProgressInterval seconds.
  void tick() {
    if (cancelled_.load(std::memory_order_relaxed) ||
        (cancel_ && cancel_->load(std::memory_order_relaxed)))
      stop();
    if (progress_ && std::this_thread::get_id() == owner_) poll();
  }

 private:
  [[noreturn]] void stop();
  void poll();
  void report();  // calls the progress function (the fit's thread only)

  const ProgressFunction& progress_;
  const std::atomic<bool>* cancel_;
  std::thread::id owner_;
  double start_, next_;
  std::atomic<bool> cancelled_{false};
  std::atomic<const char*> phase_{""};
  std::atomic<std::size_t> done_{0}, total_{0};
  std::atomic<long> pairs_{0};
  std::atomic<long> best_{0};  // nu << 32 | nv of the fewest nu x nv that held
};

/// The monitor of the fit this thread works for (nullptr: none).
FitMonitor* current_monitor();

/// Makes `m` the current monitor of this thread until destroyed (the previous one back).
class MonitorScope {
 public:
  explicit MonitorScope(FitMonitor* m);
  ~MonitorScope();
  MonitorScope(const MonitorScope&) = delete;
  MonitorScope& operator=(const MonitorScope&) = delete;

 private:
  FitMonitor* previous_;
};

/// tick() of the current monitor, if any: where a long loop may stop.
inline void tick() {
  if (FitMonitor* m = current_monitor()) m->tick();
}
/// phase() of the current monitor, if any.
inline void progress_phase(std::string_view name, std::size_t total) {
  if (FitMonitor* m = current_monitor()) m->phase(name, total);
}
/// advance() of the current monitor, if any.
inline void progress_advance(std::size_t done) {
  if (FitMonitor* m = current_monitor()) m->advance(done);
}

}  // namespace sfit::detail
