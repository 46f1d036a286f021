// check_units(): the --units option against the known units, without OpenCASCADE.
#include "cad_units.h"

#include <string>

#include "sfit/error.h"
#include "sfit/exchange/cad_writers.h"

namespace sfit::exchange {

void check_units(const std::string& units) {
  for (const detail::Unit& u : detail::kUnits)
    if (units == u.ours) return;
  std::string known;
  for (const detail::Unit& u : detail::kUnits)
    known += (known.empty() ? "" : ", ") + std::string(u.ours);
  throw Error(ErrorCode::kUsage, "unknown length unit '" + units + "' (known: " + known + ")",
              Place{.option = "--units"});
}

}  // namespace sfit::exchange
