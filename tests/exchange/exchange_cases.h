// The surfaces the exchange tests write: three small examples, synthetic closed-v and torus
// (closed uv) sets, and the other data sets of examples/.
#pragma once

#include <string>
#include <vector>

#include "sfit/surface_fit.h"

namespace sfit::test {

struct FittedCase {
  std::string name;
  bool closed_u = false, closed_v = false;
  bool bundled = true;  ///< true: the small must-pass cases; false: the other data sets
  Rows rows;
  FitResult fit;
  double diagonal = 0;  ///< of the surface's sampled bounding box
};

/// Every case whose data is present, fitted once (default tolerance 1e-3 of the diagonal),
/// cached for the test program. `missing` gets the names of data sets not found (none: all
/// are in examples/, and a missing file is an error).
const std::vector<FittedCase>& fitted_cases(std::vector<std::string>* missing = nullptr);

/// The bundled/synthetic cases only: open, closed u, closed v, closed uv.
std::vector<const FittedCase*> must_pass_cases();

/// Bounding-box diagonal of the surface sampled on an n x n grid.
double surface_diagonal(const Surface& s, int n = 50);

}  // namespace sfit::test
