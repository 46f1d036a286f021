// A B-spline surface read back from a STEP or IGES file (the inverse of cad_writers.h).
#pragma once

#include <string>

#include "sfit/surface.h"

namespace sfit::exchange {

/// Reads the one face of a STEP or IGES file, which must lie on a non-rational (or uniformly
/// weighted) B-spline surface with uniform knots, as sfit writes them: degrees, poles and
/// periodic flags as in the file, coordinates in the file's own length unit (as
/// read_sections()). Uniform knots of another spacing or start are mapped onto sfit's
/// 0, 1, 2, ... (the same shape; parameters rescaled). Runs OpenCASCADE in this process.
/// Throws Error: kInputUnreadable (missing, unreadable), kInputSyntax (not STEP/IGES that
/// OpenCASCADE parses), kInputData (no face, several faces, not a B-spline face, rational
/// weights, non-uniform knots), kUsage (a build without OpenCASCADE).
Surface read_cad_surface(const std::string& path);

}  // namespace sfit::exchange
