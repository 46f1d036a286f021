// The editor's full searches watched (sfit/progress.h): their progress for the page (GET
// /api/progress: phase, pairs tried, best so far, time), and the drop of a stale one: a full
// search started because the hand rested (or the hold's search of the fewest counts) is
// cancelled (FitOptions::cancel) when a drag step arrives, rather than finishing and then
// being replaced by the drag's next surface.
#pragma once

#include <atomic>
#include <mutex>
#include <nlohmann/json.hpp>

#include "sfit/surface_fit.h"

namespace sfit::server {

class SearchWatch {
 public:
  /// `o` with this watch's progress function and cancel flag (every fit of the session).
  FitOptions watched(FitOptions o);

  /// A drag step arrived, or the page asked (POST /api/cancel): a cancellable search under
  /// way is cancelled. True when one was.
  bool cancel();

  /// While alive, the full search it covers is cancellable (a rest, the hold's search). Every
  /// request under the session's lock begins with one (the cancel flag cleared).
  class Scope {
   public:
    Scope(SearchWatch& w, bool cancellable);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    SearchWatch& w_;
  };

  /// Counts a cancelled search; `what` names it for the server's log (standard error).
  void dropped(const char* what);

  /// {"running": bool, "phase", "done", "total", "pairs_tried", "best": [nu, nv] or null,
  /// "seconds", "dropped": searches cancelled so far}.
  nlohmann::json progress() const;

 private:
  std::atomic<bool> cancel_{false}, cancellable_{false};
  mutable std::mutex mutex_;
  nlohmann::json progress_ = nlohmann::json::object();
  bool running_ = false, in_scope_ = false;
  long dropped_ = 0;
};

}  // namespace sfit::server
