#include "search_watch.h"

#include <cstdio>
#include <string>

namespace sfit::server {

using nlohmann::json;

FitOptions SearchWatch::watched(FitOptions o) {
  o.cancel = &cancel_;
  o.progress = [this](const FitProgress& p) {
    std::lock_guard<std::mutex> lock(mutex_);
    running_ = in_scope_;  // a request's fit (not the first fit, before the server listens)
    progress_ = json{{"phase", std::string(p.phase)},
                     {"done", p.done},
                     {"total", p.total},
                     {"pairs_tried", p.pairs_tried},
                     {"best", p.best_u > 0 ? json::array({p.best_u, p.best_v}) : json(nullptr)},
                     {"seconds", p.seconds}};
    return true;
  };
  return o;
}

bool SearchWatch::cancel() {
  std::lock_guard<std::mutex> lock(mutex_);  // not between a scope's end and the next's start
  if (!cancellable_.load()) return false;
  cancel_.store(true);
  return true;
}

SearchWatch::Scope::Scope(SearchWatch& w, bool cancellable) : w_(w) {
  std::lock_guard<std::mutex> lock(w_.mutex_);
  w_.cancel_.store(false);
  w_.cancellable_.store(cancellable);
  w_.in_scope_ = true;
  w_.running_ = false;
}

SearchWatch::Scope::~Scope() {
  // A cancel never outlives its request: fits outside one (the drag watch's) run to the end.
  std::lock_guard<std::mutex> lock(w_.mutex_);
  w_.cancellable_.store(false);
  w_.cancel_.store(false);
  w_.in_scope_ = false;
  w_.running_ = false;
}

void SearchWatch::dropped(const char* what) {
  long n = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    n = ++dropped_;
  }
  std::fprintf(stderr, "sfit: %s dropped: a drag step came (%ld dropped)\n", what, n);
  std::fflush(stderr);
}

json SearchWatch::progress() const {
  std::lock_guard<std::mutex> lock(mutex_);
  json j = progress_;
  j["running"] = running_;
  j["dropped"] = dropped_;
  return j;
}

}  // namespace sfit::server
