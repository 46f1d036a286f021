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
  static const ex::detail::CadModule table{
      ex::detail::kCadModuleAbi,       SFIT_VERSION_STRING,  &ex::write_step, &ex::write_iges,
      &ex::detail::read_sections_here, &ex::read_cad_surface};
  return &table;
}
