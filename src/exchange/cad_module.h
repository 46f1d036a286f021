// STEP and IGES live in a module of their own, libsfit_cad.so, loaded on first use (private to
// sfit_exchange). Linking OpenCASCADE's 18 libraries into every program cost each start of the
// CLI and each `import sfit` about 60 ms of dynamic linking on a quiet machine (140 ms under
// load: a program that links them and does nothing against one that does not, in one run); a
// fit that writes JSON or a mesh never needs them. The module exports one C function giving
// this table; the caller checks that it comes from the same build (the same configure run:
// the table passes sfit's types by their layout) before using it.
#pragma once

#include <string>

#include "sfit/error.h"
#include "sfit/exchange/cad_writers.h"
#include "sfit/exchange/readers.h"
#include "sfit/surface.h"

namespace sfit::exchange::detail {

/// Raised whenever the table's layout or meaning changes.
inline constexpr int kCadModuleAbi = 2;
/// The name of the module's one exported function: `const CadModule* sfit_cad_module(void)`.
inline constexpr const char* kCadModuleEntry = "sfit_cad_module";

struct CadModule {
  int abi;              ///< kCadModuleAbi of the module's build
  const char* version;  ///< SFIT_VERSION_STRING of the module's build
  const char* build;    ///< SFIT_CAD_BUILD_ID: the configure run both sides were built by
  void (*write_step)(const std::string& path, const Surface& s, const CadOptions& o);
  void (*write_iges)(const std::string& path, const Surface& s, const CadOptions& o);
  SectionsFile (*read_sections_here)(const std::string& path);
  Surface (*read_cad_surface)(const std::string& path);
};

/// The loaded module (loaded once, never unloaded; after that no lock is taken). Throws
/// Error(kUsage) at `place` (the option or the file that asked for it), naming the places it
/// looked in, when no module of this very build loads.
const CadModule& cad_module(const Place& place = {});

}  // namespace sfit::exchange::detail
