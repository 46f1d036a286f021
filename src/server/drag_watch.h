// A drag whose page has gone (a tab closed mid-drag, a dropped connection) must not leave the
// session at a quick refit: when no edit has come for `timeout` while a drag's shown
// surface is not the full fit, the watch ends the drag (Session::finish_drag: the full fit,
// one undo step). A drag at rest (already the full fit) that hears nothing for 20 timeouts is
// ended too.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "session.h"

namespace sfit::server {

class DragWatch {
 public:
  /// Watches `session`, taking `mutex` (the server's session lock) to look and to act.
  DragWatch(std::mutex& mutex, Session& session, std::chrono::milliseconds timeout);
  ~DragWatch();  ///< stops the watch
  DragWatch(const DragWatch&) = delete;
  DragWatch& operator=(const DragWatch&) = delete;

  /// An edit was answered: the dragging client is there.
  void touch();
  /// While one lives, an edit is being served (a rest's full search may take longer than the
  /// timeout): the client is there, and no drag is ended. Its end touches.
  class Serving {
   public:
    explicit Serving(DragWatch& w) : w_(w) { ++w_.serving_; }
    ~Serving() {
      w_.touch();
      --w_.serving_;
    }
    Serving(const Serving&) = delete;
    Serving& operator=(const Serving&) = delete;

   private:
    DragWatch& w_;
  };
  /// Drags the watch has ended.
  long ended() const { return ended_.load(); }

 private:
  void run();
  std::mutex& mutex_;
  Session& session_;
  const std::chrono::milliseconds timeout_;
  std::atomic<std::chrono::steady_clock::rep> last_;
  std::atomic<long> ended_{0};
  std::atomic<int> serving_{0};
  std::mutex wait_mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace sfit::server
