#include "drag_watch.h"

#include <cstdio>

namespace sfit::server {

using Clock = std::chrono::steady_clock;

DragWatch::DragWatch(std::mutex& mutex, Session& session, std::chrono::milliseconds timeout)
    : mutex_(mutex),
      session_(session),
      timeout_(timeout),
      last_(Clock::now().time_since_epoch().count()),
      thread_([this] { run(); }) {}

DragWatch::~DragWatch() {
  {
    std::lock_guard<std::mutex> lock(wait_mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void DragWatch::touch() {
  last_ = Clock::now().time_since_epoch().count();
}

void DragWatch::run() {
  const auto tick = std::max(std::chrono::milliseconds(20), timeout_ / 5);
  std::unique_lock<std::mutex> wait(wait_mutex_);
  while (!wake_.wait_for(wait, tick, [this] { return stop_; })) {
    const auto asked = Clock::now();
    std::lock_guard<std::mutex> lock(mutex_);
    // A request held the session meanwhile: the client is there (its answer is touched next).
    if (Clock::now() - asked > tick) continue;
    if (!session_.dragging() || serving_.load() > 0) continue;
    const auto idle = Clock::now() - Clock::time_point(Clock::duration(last_.load()));
    if (idle < timeout_ || (session_.final() && idle < 20 * timeout_)) continue;
    try {
      session_.finish_drag();  // the full fit, one undo step
    } catch (...) {
      // finish_drag() dropped a drag the full fit refuses (the rows as before it)
    }
    ++ended_;
    std::fprintf(stderr, "sfit: a drag without an edit for %.1f s ended at the full fit\n",
                 std::chrono::duration<double>(idle).count());
    std::fflush(stderr);
  }
}

}  // namespace sfit::server
