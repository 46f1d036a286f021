// Eigen (through the sfit headers) before httplib.h: <resolv.h> defines the macro _res.
#include "api_json.h"
#include "assets.h"
#include "drag_steps.h"
#include "drag_watch.h"
#include "file_lock.h"
#include "hold.h"
#include "save_file.h"
#include "search_watch.h"
#include "session.h"
#include "sfit/error.h"
#include "sfit/io/file_names.h"
#include "sfit/io/options_json.h"
#include "sfit/io/surface_json.h"
#include "sfit/server/editor.h"
// clang-format off
#include "guarded_http.h"  // httplib.h
// clang-format on
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <random>
#include <sstream>
#include <thread>

namespace sfit::server {

using nlohmann::json;

namespace {

/// Largest request body read (bytes); a larger one gets 400.
constexpr std::size_t kMaxBody = 64u << 20;

std::string fresh_token() {
  std::random_device rd;  // /dev/urandom
  std::string t;
  static const char* hex = "0123456789abcdef";
  for (int i = 0; i < 32; ++i) t += hex[rd() & 15];
  return t;
}

bool same(const std::string& a, const std::string& b) {  // without an early exit
  if (a.size() != b.size()) return false;
  unsigned char d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d |= static_cast<unsigned char>(a[i] ^ b[i]);
  return d == 0;
}

// With a charset, httplib does not compress the response (it compresses exactly
// "application/json" and text/*): on the loopback, Brotli would cost far more than it saves.
constexpr const char* kJson = "application/json; charset=utf-8";

void reply(httplib::Response& res, int status, const json& j) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  res.set_content(j.dump(), kJson);
}

void reply_error(httplib::Response& res, int status, const std::string& message,
                 const std::string& code) {
  reply(res, status, json{{"error", message}, {"code", code}, {"place", json::object()}});
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

struct EditorServer::Impl {
  EditorConfig config;
  SearchWatch search;  // the full searches' progress, and their cancel (before the session)
  Session session;
  std::mutex mutex;  // one request at a time touches the session
  GuardedHttpServer http{GuardedHttpServer::Limits{}};
  int port = 0;
  std::string token;
  DragSteps drag_steps;  // which drag steps a newer one overtook
  bool saved_once = false;
  std::mutex run_mutex;  // run() under way (stop_within() waits for its end)
  std::condition_variable run_ended;
  bool running = false;
  FileLock file_lock{config.input};  // a second editor of INPUT opens read-only
  DragWatch watch{mutex, session, std::chrono::milliseconds(5000)};  // a drag whose page left

  explicit Impl(EditorConfig c)
      : config(std::move(c)), session(std::move(config.rows), search.watched(config.options)) {
    config.rows = Rows();
  }

  bool can_export(const std::string& ext) const {
    if (ext == "json") return true;
    if (!config.write) return false;
    for (const auto& e : config.export_formats)
      if (e == ext) return true;
    return false;
  }

  json formats() const {
    json f = json::array({"json"});
    for (const auto& e : config.export_formats)
      if (e != "json" && config.write) f.push_back(e);
    return f;
  }

  json state(bool with_rows) {
    json j = state_json(session, with_rows);
    j["input"] = config.input;
    j["exports"] = formats();
    j["saved"] = saved_once;
    j["three"] = have_three();
    j["read_only"] = !file_lock.writable();
    j["lock"] = file_lock.why();
    j["options"]["hold"] = held(session.options());
    j["units"] = config.units;
    // The rows look closed and are fitted open: the page offers closed u in one click.
    j["closed_hint"] = config.closed_note.empty() || session.options().closed_u
                           ? json(nullptr)
                           : json(config.closed_note);
    return j;
  }

  void write_export(const std::string& path, const std::string& ext) {
    if (ext == "json" &&
        !(config.write && std::find(config.export_formats.begin(), config.export_formats.end(),
                                    "json") != config.export_formats.end()))
      io::write_surface_json(path, session.result().surface, &session.result().report);
    else
      config.write(path, session.result(), session.rows());
  }

  // The export file beside INPUT: STEM-edited.EXT (never INPUT itself).
  std::string beside_input(const std::string& ext) const {
    namespace fs = std::filesystem;
    const fs::path in(config.input);
    fs::path out = in.parent_path() / (in.stem().string() + "-edited." + ext);
    if (fs::weakly_canonical(out) == fs::weakly_canonical(in))
      out = in.parent_path() / (in.stem().string() + "-edited-surface." + ext);
    return out.string();
  }

  std::string format_of(const json& body) const {
    if (!body.contains("format") || !body["format"].is_string())
      throw Error(ErrorCode::kUsage, "missing or not a string", Place{.option = "format"});
    const std::string ext = lower(body["format"].get<std::string>());
    if (!can_export(ext))
      throw Error(ErrorCode::kUsage,
                  "cannot export '" + ext + "' (known: " + formats().dump() + ")",
                  Place{.option = "format"});
    return ext;
  }

  // Runs `f` under the session lock; an Error becomes a JSON error (400 for the request's
  // fault, 500 for a write that failed), the state unchanged.
  // `cancellable`: a drag step or POST /api/cancel may cancel the full search `f` runs.
  template <class F>
  void guarded(httplib::Response& res, F&& f, bool cancellable = false) {
    try {
      std::lock_guard<std::mutex> lock(mutex);
      const SearchWatch::Scope scope(search, cancellable);
      f();
    } catch (const Error& e) {
      const bool ours = e.code() == ErrorCode::kUsage || e.code() == ErrorCode::kInputData ||
                        e.code() == ErrorCode::kToleranceNotMet;
      reply(res, ours ? 400 : 500, error_json(e));
    } catch (const std::bad_alloc&) {
      reply_error(res, 500, "out of memory", "internal");
    } catch (const std::exception& e) {
      reply_error(res, 500, std::string("internal: ") + e.what(), "internal");
    }
  }

  json body_of(const httplib::Request& req) {
    if (req.body.size() > kMaxBody)
      throw Error(ErrorCode::kUsage,
                  "request body of " + std::to_string(req.body.size()) + " bytes exceeds " +
                      std::to_string(kMaxBody),
                  Place{.option = "body"});
    if (req.body.empty()) return json::object();
    return parse_body(req.body);
  }

  void routes() {
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

    http.Get("/api/state", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        reply(res, 200, state(!(req.has_param("rows") && req.get_param_value("rows") == "0")));
      });
    });
    http.Post("/api/edit", [this](const httplib::Request& req, httplib::Response& res) {
      json body;
      std::string key;
      std::optional<std::uint64_t> ticket;  // a drag step with a seq: its arrival
      std::uint64_t seq = 0;
      try {
        body = body_of(req);
        key = client_key(body);  // takes "client" out of the edit
        if (body.contains("seq")) seq = seq_of(body["seq"]);
        if (body.contains("seq") && body.value("phase", json()) == "drag")
          ticket = drag_steps.arrive(key, seq);
      } catch (const Error& e) {
        reply(res, 400, error_json(e));
        return;
      }
      const bool drag = body.value("phase", json()) == "drag";
      const bool rest = body.value("phase", json()) == "rest";
      if (drag) search.cancel();  // a full search at rest under way is stale now
      guarded(
          res,
          [&] {
            if (ticket &&
                drag_steps.overtaken(key, *ticket, seq)) {  // a newer step came: skip this
              json j = state(false);
              j["skipped"] = true;
              reply(res, 200, j);
              return;
            }
            try {
              apply_edit(session, body);
            } catch (const Error& e) {
              if (!rest || e.code() != ErrorCode::kCancelled) throw;
              search.dropped("the full search at rest");  // the drag goes on from its quick state
              json j = state(false);
              j["skipped"] = true;
              j["cancelled"] = true;
              reply(res, 200, j);
              return;
            }
            const bool rows =
                !drag && !(req.has_param("rows") && req.get_param_value("rows") == "0");
            json j = state(rows);
            j["skipped"] = false;
            reply(res, 200, j);
          },
          rest);
    });
    // Drops a full search under way that a drag made stale (a rest's, the hold's search).
    http.Post("/api/cancel", [this](const httplib::Request&, httplib::Response& res) {
      reply(res, 200, json{{"cancelled", search.cancel()}});
    });
    // The progress of the full search under way (not behind the session's lock).
    http.Get("/api/progress", [this](const httplib::Request&, httplib::Response& res) {
      reply(res, 200, search.progress());
    });
    auto history = [this](bool undo) {
      return [this, undo](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
          body_of(req);
          const bool done = undo ? session.undo() : session.redo();
          json j = state(true);
          j["done"] = done;
          reply(res, 200, j);
        });
      };
    };
    http.Post("/api/undo", history(true));
    http.Post("/api/redo", history(false));
    // The library's option table (sfit/options.h): names, types, defaults, limits, choices.
    http.Get("/api/options-table", [this](const httplib::Request&, httplib::Response& res) {
      guarded(res, [&] { reply(res, 200, io::option_table_json()); });
    });
    http.Post("/api/options", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        const json body = body_of(req);
        session.set_options(options_with_hold(body, session, config.options.method),
                            phase_of(body));
        reply(res, 200, state(true));
      });
    });
    http.Post("/api/search", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(
          res,
          [&] {
            try {
              reply(res, 200, search_without_hold(body_of(req), session, config.options.method));
            } catch (const Error& e) {
              if (e.code() != ErrorCode::kCancelled) throw;
              search.dropped("the hold's search");
              reply(res, 200, json{{"cancelled", true}});
            }
          },
          true);
    });
    http.Post("/api/save", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        body_of(req);
        if (!file_lock.writable())
          throw Error(ErrorCode::kUsage, file_lock.why(), Place{.option = "save"});
        if (lower(io::extension_of(config.input)) != "rows")
          throw Error(ErrorCode::kUsage,
                      "save writes .rows text and '" + config.input +
                          "' is not a .rows file: export the surface instead",
                      Place{.option = "save"});
        session.finish_drag();
        const SaveResult saved = save_rows(config.input, session.rows());
        saved_once = true;
        reply(res, 200,
              json{{"saved", config.input},
                   {"written", saved.target},
                   {"backup", saved.backup},
                   {"backup_written", saved.backup_written},
                   {"weights", session.rows().weighted()},
                   {"version", session.version()}});
      });
    });
    http.Post("/api/export", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        const json body = body_of(req);
        const std::string ext = format_of(body);
        session.finish_drag();
        const std::string path = beside_input(ext);
        write_export(path, ext);
        reply(res, 200, json{{"path", path}, {"format", ext}, {"version", session.version()}});
      });
    });
    http.Get("/api/export", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(res, [&] {
        json q = json::object();
        if (req.has_param("format")) q["format"] = req.get_param_value("format");
        const std::string ext = format_of(q);
        session.finish_drag();
        namespace fs = std::filesystem;
        std::string dir = (fs::temp_directory_path() / "sfit-edit-XXXXXX").string();
        if (!mkdtemp(dir.data()))
          throw Error(ErrorCode::kOutputWrite, "cannot make a temporary folder",
                      Place{.file = dir});
        const std::string name = fs::path(config.input).stem().string() + "-edited." + ext;
        const std::string path = (fs::path(dir) / name).string();
        struct Cleanup {
          std::string d;
          ~Cleanup() {
            std::error_code ec;
            std::filesystem::remove_all(d, ec);
          }
        } cleanup{dir};
        write_export(path, ext);
        std::ifstream in(path, std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        res.set_header("Content-Disposition", "attachment; filename=\"" + name + "\"");
        res.set_header("Cache-Control", "no-store");
        res.set_content(s.str(), ext == "json" ? kJson : "application/octet-stream");
      });
    });
  }
};

EditorServer::EditorServer(EditorConfig config) : impl_(std::make_unique<Impl>(std::move(config))) {
  impl_->token = impl_->config.token.empty() ? fresh_token() : impl_->config.token;
  impl_->routes();
  const int want = impl_->config.port;
  if (want < 0 || want > 65535)
    throw Error(ErrorCode::kUsage, "port must be 0 ... 65535", Place{.option = "--port"},
                {static_cast<double>(want)});
  if (want == 0) {
    impl_->port = impl_->http.bind_to_any_port("127.0.0.1");
  } else {
    impl_->port = impl_->http.bind_to_port("127.0.0.1", want) ? want : -1;
  }
  if (impl_->port <= 0)
    throw Error(ErrorCode::kUsage,
                "cannot listen on 127.0.0.1:" + std::to_string(want) + " (in use?)",
                Place{.option = "--port"}, {static_cast<double>(want)});
}

EditorServer::~EditorServer() = default;

int EditorServer::port() const {
  return impl_->port;
}
const std::string& EditorServer::token() const {
  return impl_->token;
}
std::string EditorServer::url() const {
  return "http://127.0.0.1:" + std::to_string(impl_->port) + "/?token=" + impl_->token;
}
void EditorServer::run() {
  {
    std::lock_guard<std::mutex> lock(impl_->run_mutex);
    impl_->running = true;
  }
  impl_->http.listen_after_bind();  // returns once every request has ended
  std::lock_guard<std::mutex> lock(impl_->run_mutex);
  impl_->running = false;
  impl_->run_ended.notify_all();
}
void EditorServer::stop() {
  impl_->http.stop();
}
bool EditorServer::stop_within(std::chrono::milliseconds grace) {
  stop();
  std::unique_lock<std::mutex> lock(impl_->run_mutex);
  return impl_->run_ended.wait_for(lock, grace, [&] { return !impl_->running; });
}

}  // namespace sfit::server
