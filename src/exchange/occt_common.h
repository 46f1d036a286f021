// Shared by the OpenCASCADE parts of sfit_exchange (private header).
#pragma once

#include <Geom_BSplineSurface.hxx>
#include <Standard_Failure.hxx>
#include <string>

#include "sfit/surface.h"

namespace sfit::exchange::detail {

/// The surface as OCCT sees it: same degrees, poles, knots 0, 1, ... (distinct values with
/// multiplicities: degree + 1 at the ends of an open direction, 1 everywhere in a periodic
/// one) and the periodic flags, so it evaluates to Surface::evaluate() at the same (u, v).
Handle(Geom_BSplineSurface) to_occt(const Surface& surface);

/// Turns OCCT's console chatter (transfer statistics) down to failures only.
void quiet_occt();

/// "Standard_Failure: message" for error texts.
std::string describe(const Standard_Failure& failure);

}  // namespace sfit::exchange::detail
