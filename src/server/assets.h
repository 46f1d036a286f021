// The page's files, embedded into the binary at build time (cmake/embed_files.cmake turns
// editor/ and the three.js module build into a generated source), so nothing is fetched at
// run time.
#pragma once

#include <cstddef>
#include <string_view>

namespace sfit::server {

struct Asset {
  std::string_view path;  ///< URL path, e.g. "/index.html", "/vendor/three.module.min.js"
  std::string_view mime;
  std::string_view data;
};

/// The embedded files; an unknown path gives nullptr.
const Asset* find_asset(std::string_view path);
/// False when the build found no three.js (editor/node_modules missing): the page says so.
bool have_three();

}  // namespace sfit::server
