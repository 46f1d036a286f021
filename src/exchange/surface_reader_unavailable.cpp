// read_cad_surface() in a build without OpenCASCADE: a clear usage error.
#include "sfit/error.h"
#include "sfit/exchange/surface_reader.h"

namespace sfit::exchange {

Surface read_cad_surface(const std::string& path) {
  throw Error(ErrorCode::kUsage, "STEP and IGES are off: this sfit was built without OpenCASCADE",
              Place{.file = path});
}

}  // namespace sfit::exchange
