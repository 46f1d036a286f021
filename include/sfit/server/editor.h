// `sfit edit`: a local HTTP server for the browser editor. The designer moves, adds and
// deletes data points and rows; every change refits through IncrementalFit and the page shows
// the new surface. docs/editor.md describes the page and the JSON API.
#pragma once

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
  /// Serves until stop() (thread-safe, callable from any thread).
  void run();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Serves until SIGINT or SIGTERM, then returns (the signals are blocked in every thread and
/// waited for, so the server ends cleanly). `on_ready` runs once the server listens.
void serve_until_signal(EditorServer& server, const std::function<void()>& on_ready);

}  // namespace sfit::server
