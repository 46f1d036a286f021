// serve_until_signal(): `sfit edit`'s life, from listening to SIGINT or SIGTERM.
#include <pthread.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include "sfit/server/editor.h"

namespace sfit::server {

bool serve_until_signal(EditorServer& server, const std::function<void()>& on_ready) {
  sigset_t set, old;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &set, &old);  // the server's threads inherit the mask
  // Shared: a thread left behind (detached below) may still set it.
  auto ended = std::make_shared<std::atomic<bool>>(false);
  std::thread t([&server, ended] {
    server.run();
    *ended = true;
  });
  if (on_ready) on_ready();
  const timespec tick{0, 200'000'000};
  while (!*ended) {
    const int sig = sigtimedwait(&set, nullptr, &tick);
    if (sig == SIGINT || sig == SIGTERM) break;
  }
  // Requests being read end within 0.1 s, idle connections within 1 s; a refit under way
  // is abandoned (the caller ends the process): nothing of it is written.
  const bool clean = server.stop_within(std::chrono::milliseconds(1500));
  if (clean)
    t.join();
  else
    t.detach();
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return clean;
}

}  // namespace sfit::server
