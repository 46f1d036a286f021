// STEP and IGES through the CAD module (cad_module.h): the public functions of cad_writers.h,
// readers.h and surface_reader.h that need OpenCASCADE load libsfit_cad.so on first use and
// call it. Where the module is looked for, in this order:
//   1. the file named by the environment variable SFIT_CAD_MODULE, if set (and only there);
//   2. beside the program or library that holds this code, and where an install puts the
//      module relative to it (bin/ -> lib/sfit/, lib/ -> lib/sfit/, the Python package ->
//      lib/sfit/: SFIT_CAD_RELATIVE, made by CMake from the install layout);
//   3. the install prefix's lib/sfit/ (SFIT_CAD_INSTALLED);
//   4. the build tree (SFIT_CAD_BUILT), for programs run where they were built (first, for a
//      program that is itself in the build tree).
// A module of another build (another configure run: SFIT_CAD_BUILD_ID) is passed over, so an
// old install never serves a new build.
#include <dlfcn.h>

#include <atomic>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "cad_module.h"
#include "section_child.h"
#include "sfit/error.h"
#include "sfit/exchange/surface_reader.h"
#include "sfit/version.h"

namespace sfit::exchange {
namespace detail {
namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string part; std::getline(in, part, ':');)
    if (!part.empty()) out.push_back(part);
  return out;
}

std::vector<std::string> candidates() {
  constexpr const char* kName = "libsfit_cad.so";
  if (const char* env = std::getenv("SFIT_CAD_MODULE"); env && *env) return {env};
  std::vector<std::string> out;
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&candidates), &info) && info.dli_fname && *info.dli_fname) {
    std::error_code ec;
    auto self = std::filesystem::canonical(info.dli_fname, ec);
    if (!ec) {
      // A program of the build tree takes the build tree's module first.
      const std::string tree = SFIT_CAD_BUILD_TREE;
      if (self.string().rfind(tree + "/", 0) == 0) out.push_back(SFIT_CAD_BUILT);
      const auto dir = self.parent_path();
      out.push_back((dir / kName).string());
      for (const std::string& rel : split(SFIT_CAD_RELATIVE))
        out.push_back((dir / rel / kName).lexically_normal().string());
    }
  }
  out.push_back(SFIT_CAD_INSTALLED);
  out.push_back(SFIT_CAD_BUILT);
  return out;
}

const CadModule* load(std::string& why, std::string& looked) {
  for (const std::string& path : candidates()) {
    looked += (looked.empty() ? "" : ", ") + path;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) continue;
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      if (why.empty()) why = ::dlerror();
      continue;
    }
    using Entry = const CadModule* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(handle, kCadModuleEntry));
    const CadModule* m = entry ? entry() : nullptr;
    if (m && m->abi == kCadModuleAbi && std::string(m->version) == SFIT_VERSION_STRING &&
        std::string(m->build) == SFIT_CAD_BUILD_ID)
      return m;  // never unloaded: its code may be on the stack of a later error
    if (why.empty())
      why = path + (m ? " is of another build of sfit (" + std::string(m->version) + ")"
                      : " is not sfit's CAD module");
    ::dlclose(handle);
  }
  return nullptr;
}

}  // namespace

const CadModule& cad_module(const Place& place) {
  static std::atomic<const CadModule*> loaded{nullptr};
  if (const CadModule* m = loaded.load(std::memory_order_acquire)) return *m;
  static std::mutex mutex;
  std::lock_guard lock(mutex);
  if (const CadModule* m = loaded.load(std::memory_order_relaxed)) return *m;
  std::string why, looked;
  const CadModule* m = load(why, looked);
  if (!m)
    throw Error(ErrorCode::kUsage,
                "STEP and IGES need sfit's CAD module (libsfit_cad.so, OpenCASCADE), which " +
                    (why.empty() ? std::string("is not installed") : "did not load: " + why) +
                    " (looked in " + looked + ")",
                place);
  loaded.store(m, std::memory_order_release);
  return *m;
}

SectionsFile read_sections_here(const std::string& path) {
  return cad_module(Place{.file = path}).read_sections_here(path);
}

}  // namespace detail

void require_cad(const std::string& option) {
  detail::cad_module(Place{.option = option});
}

void write_step(const std::string& path, const Surface& s, const CadOptions& o) {
  check_units(o.units);
  detail::cad_module(Place{.file = path}).write_step(path, s, o);
}

void write_iges(const std::string& path, const Surface& s, const CadOptions& o) {
  check_units(o.units);
  detail::cad_module(Place{.file = path}).write_iges(path, s, o);
}

Surface read_cad_surface(const std::string& path) {
  return detail::cad_module(Place{.file = path}).read_cad_surface(path);
}

}  // namespace sfit::exchange
