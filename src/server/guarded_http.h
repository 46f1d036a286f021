// cpp-httplib's server with limits against slow clients, applied before any request is read:
// at most `connections` connections at a time (more are answered 503 and closed at once),
// a connection's first byte within `request_read`, and every request (its line, headers and
// body) read within `request_read` of its first byte, however slowly it drips; reads also end
// within 0.1 s of stop(). Debian's httplib
// (0.11) times out each read, not a whole request, and its pool has max(8, cores - 1)
// threads, so 8 clients dripping a byte a second held every worker for good.
#pragma once

// Eigen (through the sfit headers) before httplib.h: <resolv.h> defines the macro _res.
#include <httplib.h>

#include <atomic>
#include <chrono>

namespace sfit::server {

class GuardedHttpServer : public httplib::Server {
 public:
  struct Limits {
    int connections = 32;  ///< open at a time; the pool has this many threads and 8 more
    std::chrono::milliseconds request_read{10000};
  };
  explicit GuardedHttpServer(Limits limits);
  const Limits& limits() const { return limits_; }
  /// Connections open now.
  int open() const { return open_.load(); }
  bool stopping() const { return svr_sock_ == INVALID_SOCKET; }

 private:
  bool process_and_close_socket(socket_t sock) override;
  Limits limits_;
  std::atomic<int> open_{0};
};

}  // namespace sfit::server
