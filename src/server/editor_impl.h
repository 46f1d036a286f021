// The editor server's state (EditorServer::Impl), private to src/server; its routes are
// defined in editor_server.cpp (the session's API), http_guards.cpp (the HTTP guards and the
// page) and file_routes.cpp (save and exports).
#pragma once

// Eigen (through the sfit headers) before httplib.h: <resolv.h> defines the macro _res.
#include "api_json.h"
#include "assets.h"
#include "drag_steps.h"
#include "drag_watch.h"
#include "file_lock.h"
#include "hold.h"
#include "influence.h"
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

/// Largest request body read (bytes); a larger one gets 400.
constexpr std::size_t kMaxBody = 64u << 20;

// With a charset, httplib does not compress the response (it compresses exactly
// "application/json" and text/*): on the loopback, Brotli would cost far more than it saves.
constexpr const char* kJson = "application/json; charset=utf-8";

inline void reply(httplib::Response& res, int status, const json& j) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  res.set_content(j.dump(), kJson);
}

inline void reply_error(httplib::Response& res, int status, const std::string& message,
                        const std::string& code) {
  reply(res, status, json{{"error", message}, {"code", code}, {"place", json::object()}});
}

inline std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

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

  json state(bool with_rows, Pack pack = Pack::kNone) {
    json j = state_json(session, with_rows, pack);
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
    guard_http();
    page_routes();
    session_routes();
    file_routes();
  }
  void guard_http();      // limits, Host and token checks, errors (http_guards.cpp)
  void page_routes();     // the page and its assets (http_guards.cpp)
  void session_routes();  // state, edits, history, options, search (editor_server.cpp)
  void file_routes();     // save and exports (file_routes.cpp)
};

}  // namespace sfit::server
