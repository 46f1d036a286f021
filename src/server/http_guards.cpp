// The editor server's HTTP guards (limits, the Host and token checks, error answers) and the
// page's routes.
#include "editor_impl.h"

namespace sfit::server {

namespace {

bool same(const std::string& a, const std::string& b) {  // without an early exit
  if (a.size() != b.size()) return false;
  unsigned char d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d |= static_cast<unsigned char>(a[i] ^ b[i]);
  return d == 0;
}

}  // namespace

void EditorServer::Impl::guard_http() {
  http.set_payload_max_length(kMaxBody);
  // Idle keep-alive connections hold a worker until this timeout: short, so stop() is quick.
  http.set_keep_alive_timeout(1);
  // Headers and body go out as separate writes: without TCP_NODELAY, Nagle's algorithm and
  // the client's delayed ACK add some 40 ms to every response.
  http.set_tcp_nodelay(true);
  // A drag's client is there while its edits come (a page's polling does not count).
  http.set_logger([this](const httplib::Request& req, const httplib::Response&) {
    if (req.path == "/api/edit") watch.touch();
  });
  // httplib's default also sets SO_REUSEPORT, which would let a second editor bind the same
  // port and share its connections: only SO_REUSEADDR (a port in TIME_WAIT may be reused).
  http.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    const std::string host = req.get_header_value("Host");
    const std::string p = std::to_string(port);
    if (const std::size_t hosts = req.get_header_value_count("Host"); hosts != 1) {
      reply_error(res, 403, "exactly one Host header is accepted, got " + std::to_string(hosts),
                  "host");
      return httplib::Server::HandlerResponse::Handled;
    }
    if (host != "127.0.0.1:" + p && host != "localhost:" + p) {
      reply_error(res, 403,
                  "Host '" + host + "' refused: only 127.0.0.1:" + p + " or localhost:" + p,
                  "host");
      return httplib::Server::HandlerResponse::Handled;
    }
    if (req.path.rfind("/api/", 0) == 0) {
      std::string t = req.get_header_value("X-Sfit-Token");
      if (t.empty() && req.has_param("token")) t = req.get_param_value("token");
      if (!same(t, token)) {
        reply_error(res, 403,
                    t.empty() ? "missing token (X-Sfit-Token header or ?token=)" : "wrong token",
                    "token");
        return httplib::Server::HandlerResponse::Handled;
      }
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  http.set_error_handler(httplib::Server::HandlerWithResponse([](const httplib::Request& req,
                                                                 httplib::Response& res) {
    if (res.status == 413)  // body over the limit: the request's fault, as any bad request
      reply_error(res, 400,
                  "request body of " + req.get_header_value("Content-Length") +
                      " bytes exceeds the limit of " + std::to_string(kMaxBody),
                  "usage");
    else if (res.status == 404)
      reply_error(res, 404, "no such page or API call: " + req.method + " " + req.path, "usage");
    else if (res.body.empty())
      reply_error(res, res.status, "HTTP " + std::to_string(res.status), "usage");
    return httplib::Server::HandlerResponse::Handled;
  }));
}

void EditorServer::Impl::page_routes() {
  auto page = [](const httplib::Request& req, httplib::Response& res) {
    const std::string path = req.path == "/" ? "/index.html" : req.path;
    const Asset* a = find_asset(path);
    if (!a) {
      reply_error(res, 404, "no such page: " + req.path, "usage");
      return;
    }
    res.set_header("X-Content-Type-Options", "nosniff");
    res.set_header("Content-Security-Policy",
                   "default-src 'self'; script-src 'self' 'unsafe-inline'; "
                   "style-src 'self' 'unsafe-inline'; img-src 'self' data: blob:");
    res.set_content(std::string(a->data), std::string(a->mime));
  };
  http.Get("/", page);
  http.Get("/favicon.ico",
           [](const httplib::Request&, httplib::Response& res) { res.status = 204; });
  http.Get(R"(/(index\.html|js/[a-z_]+\.js|style\.css|vendor/[A-Za-z_.]+\.js))", page);
}

}  // namespace sfit::server
