// The editor's server (sfit/server/editor.h): the session's API; editor_impl.h holds its state.
#include "editor_impl.h"

namespace sfit::server {

namespace {

std::string fresh_token() {
  std::random_device rd;  // /dev/urandom
  std::string t;
  static const char* hex = "0123456789abcdef";
  for (int i = 0; i < 32; ++i) t += hex[rd() & 15];
  return t;
}

}  // namespace

void EditorServer::Impl::session_routes() {
  http.Get("/api/state", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] {
      reply(res, 200, state(!(req.has_param("rows") && req.get_param_value("rows") == "0")));
    });
  });
  http.Post("/api/edit", [this](const httplib::Request& req, httplib::Response& res) {
    const DragWatch::Serving serving(watch);  // the client is there while its edit is served
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
    // ?pack=1: the control points as packed doubles, ?pack=f32 as floats for drawing
    // (api_json.h), e.g. for a drag's steps.
    const std::string pack_as = req.has_param("pack") ? req.get_param_value("pack") : "";
    const Pack packed = pack_as == "1" ? Pack::kF64 : pack_as == "f32" ? Pack::kF32 : Pack::kNone;
    if (drag) search.cancel();  // a full search at rest under way is stale now
    guarded(
        res,
        [&] {
          if (ticket && drag_steps.overtaken(key, *ticket, seq)) {  // a newer step came: skip this
            json j = state(false, packed);
            j["skipped"] = true;
            reply(res, 200, j);
            return;
          }
          try {
            apply_edit(session, body);
          } catch (const Error& e) {
            if (!rest || e.code() != ErrorCode::kCancelled) throw;
            search.dropped("the full search at rest");  // the drag goes on from its quick state
            json j = state(false, packed);
            j["skipped"] = true;
            j["cancelled"] = true;
            reply(res, 200, j);
            return;
          }
          const bool rows = !drag && !(req.has_param("rows") && req.get_param_value("rows") == "0");
          json j = state(rows, packed);
          j["skipped"] = false;
          reply(res, 200, j);
        },
        rest);
  });
  // The influence of one point on the quick refit, for the page's prediction of a drag
  // (influence.h).
  http.Post("/api/influence", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] {
      const json body = body_of(req);
      const auto at = [&](const char* key) {
        if (!body.contains(key) || !body[key].is_number_unsigned())
          throw Error(ErrorCode::kUsage, "must be a whole number >= 0", Place{.option = key});
        return body[key].get<std::size_t>();
      };
      reply(res, 200, drag_influence(session, at("row"), at("index")));
    });
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
      session.set_options(options_with_hold(body, session, config.options.method), phase_of(body));
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
}

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
std::string EditorServer::best_effort() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->session.best_effort();
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
