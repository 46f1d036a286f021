// STEP and IGES written by OpenCASCADE (its own target, sfit_exchange: the core never sees
// OCCT). The surface becomes a Geom_BSplineSurface with the same knots, poles and degrees, a
// periodic direction flagged periodic (distinct poles, unit multiplicities), so a CAD reader
// finds one smooth closed surface with no crack or kink.
#pragma once

#include <string>

#include "sfit/surface.h"

namespace sfit::exchange {

/// Length units a STEP/IGES file can state; the coordinates are written unchanged.
/// Known: "mm", "cm", "m", "km", "in", "ft", "mi", "um" (as OCCT names them).
struct CadOptions {
  std::string units = "mm";
  std::string name;  ///< product / file name in the header ("" : the file's stem)
};

/// Throws Error(kUsage, option "--units") unless `units` is one of the known names.
void check_units(const std::string& units);

/// Loads the part that writes and reads STEP and IGES (OpenCASCADE, in a module of its own
/// loaded on first use) now, so that a missing install is refused before any work: throws
/// Error(kUsage, option `option`) where it cannot.
void require_cad(const std::string& option);

/// STEP AP214 (AUTOMOTIVE_DESIGN): one ADVANCED_FACE on the B_SPLINE_SURFACE_WITH_KNOTS in a
/// shell-based surface model, the length unit stated as an SI or conversion-based unit.
/// Throws Error(kOutputWrite) if OCCT refuses the surface or the file.
void write_step(const std::string& path, const Surface& surface, const CadOptions& options = {});

/// IGES 5.3: a trimmed surface (entity 144) on the B-spline surface (entity 128, polynomial
/// with unit weights, PROP4/PROP5 set for periodic directions), units in the global section.
void write_iges(const std::string& path, const Surface& surface, const CadOptions& options = {});

}  // namespace sfit::exchange
