// The length units a STEP/IGES file can state (private to sfit_exchange and its CAD module):
// plain data, without OpenCASCADE, so that the options are checked before the module loads.
#pragma once

#include <array>

namespace sfit::exchange::detail {

/// Our unit names, OCCT's (write.step.unit, IGES global section) and the size in millimetres.
struct Unit {
  const char* ours;
  const char* occt;
  double mm;
};
inline constexpr std::array<Unit, 8> kUnits{{{"mm", "MM", 1.0},
                                             {"cm", "CM", 10.0},
                                             {"m", "M", 1000.0},
                                             {"km", "KM", 1e6},
                                             {"um", "UM", 1e-3},
                                             {"in", "INCH", 25.4},
                                             {"ft", "FT", 304.8},
                                             {"mi", "MI", 1609344.0}}};

}  // namespace sfit::exchange::detail
