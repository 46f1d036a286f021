#include "guarded_http.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>

namespace sfit::server {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kSliceMs = 100;  // waits are cut into slices that notice stop()

// Waits until `sock` has `events` or `deadline` passes or the server stops.
bool wait_for(const GuardedHttpServer& server, socket_t sock, short events,
              Clock::time_point deadline) {
  for (;;) {
    if (server.stopping()) return false;
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return false;
    pollfd p{sock, events, 0};
    const int n = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, kSliceMs)));
    if (n > 0) return true;
    if (n < 0 && errno != EINTR) return false;
  }
}

void address_of(socket_t sock, bool peer, std::string& ip, int& port) {
  sockaddr_storage a{};
  socklen_t len = sizeof a;
  const int rc = peer ? ::getpeername(sock, reinterpret_cast<sockaddr*>(&a), &len)
                      : ::getsockname(sock, reinterpret_cast<sockaddr*>(&a), &len);
  if (rc != 0) return;
  char buf[INET6_ADDRSTRLEN] = {};
  if (a.ss_family == AF_INET) {
    const auto* v4 = reinterpret_cast<const sockaddr_in*>(&a);
    ::inet_ntop(AF_INET, &v4->sin_addr, buf, sizeof buf);
    port = ntohs(v4->sin_port);
  } else if (a.ss_family == AF_INET6) {
    const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&a);
    ::inet_ntop(AF_INET6, &v6->sin6_addr, buf, sizeof buf);
    port = ntohs(v6->sin6_port);
  }
  ip = buf;
}

// A socket stream whose reads all end by one deadline (the request's), buffered like
// httplib's own (its line reader asks for one byte at a time).
class DeadlineStream : public httplib::Stream {
 public:
  DeadlineStream(const GuardedHttpServer& server, socket_t sock, Clock::time_point deadline)
      : server_(server), sock_(sock), deadline_(deadline) {}

  bool is_readable() const override {
    return begin_ < end_ || wait_for(server_, sock_, POLLIN, deadline_);
  }
  bool is_writable() const override {
    return wait_for(server_, sock_, POLLOUT, Clock::now() + std::chrono::seconds(5));
  }
  ssize_t read(char* ptr, size_t size) override {
    if (begin_ == end_) {
      if (!wait_for(server_, sock_, POLLIN, deadline_)) return -1;
      if (size >= sizeof buf_) return receive(ptr, size);
      const ssize_t n = receive(buf_, sizeof buf_);
      if (n <= 0) return n;
      begin_ = 0;
      end_ = static_cast<size_t>(n);
    }
    const size_t n = std::min(size, end_ - begin_);
    std::memcpy(ptr, buf_ + begin_, n);
    begin_ += n;
    return static_cast<ssize_t>(n);
  }
  ssize_t write(const char* ptr, size_t size) override {
    if (!is_writable()) return -1;
    for (;;) {
      const ssize_t n = ::send(sock_, ptr, size, MSG_NOSIGNAL);
      if (n < 0 && errno == EINTR) continue;
      return n;
    }
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    address_of(sock_, true, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    address_of(sock_, false, ip, port);
  }
  socket_t socket() const override { return sock_; }

 private:
  ssize_t receive(char* ptr, size_t size) {
    for (;;) {
      const ssize_t n = ::recv(sock_, ptr, size, 0);
      if (n < 0 && errno == EINTR) continue;
      return n;
    }
  }
  const GuardedHttpServer& server_;
  socket_t sock_;
  Clock::time_point deadline_;
  char buf_[4096];
  size_t begin_ = 0, end_ = 0;
};

// The answer past the connection cap, written before anything is read.
std::string busy_reply(int cap) {
  const std::string body = "{\"error\":\"too many connections (more than " + std::to_string(cap) +
                           "): try again\",\"code\":\"busy\",\"place\":{}}";
  return "HTTP/1.1 503 Service Unavailable\r\nContent-Type: application/json; charset=utf-8\r\n"
         "Connection: close\r\nContent-Length: " +
         std::to_string(body.size()) + "\r\n\r\n" + body;
}

}  // namespace

GuardedHttpServer::GuardedHttpServer(Limits limits) : limits_(limits) {
  const std::size_t threads = static_cast<std::size_t>(limits_.connections) + 8;
  new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
}

bool GuardedHttpServer::process_and_close_socket(socket_t sock) {
  struct Close {
    GuardedHttpServer& s;
    socket_t sock;
    ~Close() {
      s.open_.fetch_sub(1);
      ::shutdown(sock, SHUT_RDWR);
      ::close(sock);
    }
  } close{*this, sock};
  if (open_.fetch_add(1) >= limits_.connections) {  // answered before a byte is read
    const std::string busy = busy_reply(limits_.connections);
    (void)!::send(sock, busy.data(), busy.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    return false;
  }
  for (std::size_t left = keep_alive_max_count_; left > 0; --left) {
    // The first byte of the connection's first request within the request time (a client
    // may open the connection well before it sends), of the next ones within keep-alive's.
    const auto wait = left == keep_alive_max_count_
                          ? Clock::now() + limits_.request_read
                          : Clock::now() + std::chrono::seconds(keep_alive_timeout_sec_);
    if (!wait_for(*this, sock, POLLIN, wait)) break;
    DeadlineStream strm(*this, sock, Clock::now() + limits_.request_read);
    bool closed = false;
    if (!process_request(strm, left == 1, closed, nullptr) || closed) break;
  }
  return true;
}

}  // namespace sfit::server
