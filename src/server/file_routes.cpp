// The editor server's routes that write files: save (the rows back to INPUT, with its backup)
// and the exports (beside INPUT, or downloaded).
#include "editor_impl.h"

namespace sfit::server {

void EditorServer::Impl::file_routes() {
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
        throw Error(ErrorCode::kOutputWrite, "cannot make a temporary folder", Place{.file = dir});
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

}  // namespace sfit::server
