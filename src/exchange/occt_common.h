// Shared by the OpenCASCADE parts of sfit_exchange (private header).
#pragma once

#include <Geom_BSplineSurface.hxx>
#include <Interface_Static.hxx>
#include <Standard_Failure.hxx>
#include <UnitsMethods.hxx>
#include <array>
#include <string>

#include "cad_units.h"
#include "sfit/surface.h"

namespace sfit::exchange::detail {

/// The surface as OCCT sees it: same degrees, poles, knots (distinct values with
/// multiplicities: uniform knots as 0, 1, ... with degree + 1 at the ends of an open direction
/// and 1 everywhere in a periodic one; non-uniform knots as KnotVector::breaks() gives them)
/// and the periodic flags, so it evaluates to Surface::evaluate() at the same (u, v).
Handle(Geom_BSplineSurface) to_occt(const Surface& surface);

/// The unit called `ours` ("mm", "m", ...), or nullptr.
const Unit* unit_named(const std::string& ours);
/// The unit of a size in millimetres (1000: "m"), within 1e-9; nullptr if none.
const Unit* unit_of_size(double mm);
/// The unit of a STEP file from the length unit names OCCT reads (MILLIMETRE, METRE, INCH,
/// ...); nullptr if none of ours.
const Unit* step_unit(std::string name);
/// The unit of an IGES file from its global section's unit flag; nullptr if none of ours.
const Unit* iges_unit(int flag);

/// OCCT keeps the session's length unit in globals (Interface_Static and UnitsMethods) and
/// scales shapes between it and a file's unit. Sets the session unit to `u` for one transfer
/// (so coordinates stay in the file's unit), and restores the caller's afterwards.
class SessionUnit {
 public:
  explicit SessionUnit(const Unit& u)
      : static_(Interface_Static::IsSet("xstep.cascade.unit")
                    ? Interface_Static::CVal("xstep.cascade.unit")
                    : "MM"),
        methods_(UnitsMethods::GetCasCadeLengthUnit()) {
    Interface_Static::SetCVal("xstep.cascade.unit", u.occt);
    UnitsMethods::SetCasCadeLengthUnit(u.mm);
  }
  ~SessionUnit() {
    Interface_Static::SetCVal("xstep.cascade.unit", static_.c_str());
    UnitsMethods::SetCasCadeLengthUnit(methods_);
  }
  SessionUnit(const SessionUnit&) = delete;
  SessionUnit& operator=(const SessionUnit&) = delete;

 private:
  std::string static_;
  double methods_;
};

/// Silences OCCT's console output (transfer statistics, coloured messages on stdout): the
/// default printers are removed; sfit reports failures itself from the return statuses.
void quiet_occt();

/// "Standard_Failure: message" for error texts.
std::string describe(const Standard_Failure& failure);

}  // namespace sfit::exchange::detail
