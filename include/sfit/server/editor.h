// `sfit edit`: a local HTTP server for the browser editor. The designer moves, adds and
// deletes data points and rows; every change refits through IncrementalFit and the page shows
// the new surface. docs/editor.md describes the page, docs/editor-api.md the JSON API.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::server {

/// Writes the surface of `fit` (for the data `rows`) to `path` in the format of its extension,
/// atomically (the CLI passes the writers `sfit fit -o` uses).
using ExportWriter =
    std::function<void(const std::string& path, const FitResult& fit, const Rows& rows)>;

struct EditorConfig {
  std::string input;   ///< the edited file: saved back to (.rows), exports written beside it
  Rows rows;           ///< its rows
  FitOptions options;  ///< the fit's options, tolerance absolute
  int port = 0;        ///< 0: a free port
  std::string token;   ///< empty: a fresh random one
  ExportWriter write;  ///< export writer; may be empty (then only JSON is exported)
  std::vector<std::string> export_formats;  ///< extensions `write` handles ("json", "step", ...)
  std::string units;        ///< the data's length unit (as --units states it), shown with T
  std::string closed_note;  ///< the CLI's note on closed rows (the page offers closed u), or ""
};

class EditorServer {
 public:
  /// Fits the rows (Error as fit_surface() throws) and binds 127.0.0.1:port (Error(kUsage,
  /// option "--port") if it cannot).
  explicit EditorServer(EditorConfig config);
  ~EditorServer();
  EditorServer(const EditorServer&) = delete;
  EditorServer& operator=(const EditorServer&) = delete;

  int port() const;
  const std::string& token() const;
  /// http://127.0.0.1:PORT/?token=TOKEN
  std::string url() const;
  /// Why the surface shown is only the best found (no surface within T; the page says so
  /// too), or "" when the count search found one.
  std::string best_effort() const;
  /// Serves until stop() (thread-safe, callable from any thread); returns once every
  /// request under way has ended.
  void run();
  void stop();
  /// stop(), then waits up to `grace` for run() to return: false when a request (a long
  /// refit) is still under way; the caller may then end the process without waiting for it.
  bool stop_within(std::chrono::milliseconds grace);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Serves until SIGINT or SIGTERM, then stops (the signals are blocked in every thread and
/// waited for). `on_ready` runs once the server listens. Returns true when every request
/// ended within 1.5 s of the signal; false when one (a long refit) still runs: its thread is
/// left running and the caller must end the process promptly (std::_Exit), as `sfit edit` does.
bool serve_until_signal(EditorServer& server, const std::function<void()>& on_ready);

}  // namespace sfit::server
