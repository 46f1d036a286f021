// The surfaces the exchange tests write: the bundled examples (always there), synthetic
// closed-v and torus (closed uv) sets, and the shared data sets where ../shared/data exists.
#pragma once

#include <string>
#include <vector>

#include "sfit/surface_fit.h"

namespace sfit::test {

struct FittedCase {
  std::string name;
  bool closed_u = false, closed_v = false;
  bool bundled = true;  ///< false: from ../shared/data (may be missing)
  Rows rows;
  FitResult fit;
  double diagonal = 0;  ///< of the surface's sampled bounding box
};

/// Every case whose data is present, fitted once (default tolerance 1e-3 of the diagonal),
/// cached for the test program. `missing` gets the names of shared sets not found.
const std::vector<FittedCase>& fitted_cases(std::vector<std::string>* missing = nullptr);

/// The bundled/synthetic cases only: open, closed u, closed v, closed uv.
std::vector<const FittedCase*> must_pass_cases();

/// Bounding-box diagonal of the surface sampled on an n x n grid.
double surface_diagonal(const Surface& s, int n = 50);

}  // namespace sfit::test
