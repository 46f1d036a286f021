// STEP and IGES in a build without OpenCASCADE (-DSFIT_BUILD_EXCHANGE_CAD=OFF, or OpenCASCADE
// not found): the same functions, each refusing with a clear usage error, so that the meshes
// and VTK files of sfit::exchange still work.
#include <string>

#include "sfit/error.h"
#include "sfit/exchange/cad_writers.h"
#include "sfit/exchange/readers.h"
#include "sfit/io/file_names.h"

namespace sfit::exchange {

namespace {

[[noreturn]] void unavailable(const std::string& path) {
  throw Error(ErrorCode::kUsage, "STEP and IGES are off: this sfit was built without OpenCASCADE",
              Place{.file = path});
}

}  // namespace

void check_units(const std::string&) {}  // units matter only to STEP and IGES

void require_cad(const std::string& option) {
  throw Error(ErrorCode::kUsage, "STEP and IGES are off: this sfit was built without OpenCASCADE",
              Place{.option = option});
}

void write_step(const std::string& path, const Surface&, const CadOptions&) {
  unavailable(path);
}

void write_iges(const std::string& path, const Surface&, const CadOptions&) {
  unavailable(path);
}

bool is_exchange_input(const std::string& path) {
  const std::string e = io::extension_of(path);
  return e == "step" || e == "stp" || e == "igs" || e == "iges";
}

SectionsFile read_sections(const std::string& path, const SectionReadOptions&) {
  unavailable(path);
}

}  // namespace sfit::exchange
