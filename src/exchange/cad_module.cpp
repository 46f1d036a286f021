// The entry of libsfit_cad.so (cad_module.h): the OpenCASCADE functions of this module in one
// table. Everything else in the module is hidden (CMake: visibility hidden, static libraries'
// symbols excluded), so it never clashes with the program's own copies.
#include "cad_module.h"

#include "section_child.h"
#include "sfit/exchange/surface_reader.h"
#include "sfit/version.h"

extern "C" __attribute__((visibility("default"))) const sfit::exchange::detail::CadModule*
sfit_cad_module() {
  namespace ex = sfit::exchange;
  static const ex::detail::CadModule table{.abi = ex::detail::kCadModuleAbi,
                                           .version = SFIT_VERSION_STRING,
                                           .build = SFIT_CAD_BUILD_ID,
                                           .write_step = &ex::write_step,
                                           .write_iges = &ex::write_iges,
                                           .read_sections_here = &ex::detail::read_sections_here,
                                           .read_cad_surface = &ex::read_cad_surface};
  return &table;
}
