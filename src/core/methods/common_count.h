// The re-representation of the curve stage's curves on one common count (docs/method.md 4) of
// the two-stage method (FitMethod::kSfit01), for the rows and for the columns alike: every
// curve re-represented at the largest count, raised until every curve holds. Private to the
// two-stage method (sfit01_*.cpp).
#pragma once

#include <span>
#include <vector>

#include "curve_stage.h"
#include "rerepresent.h"

namespace sfit::detail {

/// The curves on the common count `common` (the first tried: `first_common`), how many needed
/// repair rounds, and the parameters they share (with shared_params).
struct Represented {
  std::vector<Rerepresentation> curves;
  int first_common = 0, common = 0;
  int repaired = 0;
  std::vector<double> shared_parameters;
};

/// Re-represents every curve on one common count, starting at max(degree + 1, counts) and
/// raising it until every curve holds (the guarantee's first half). `reuse` (optional) holds
/// earlier re-representations valid at `reuse_count` for curves not marked in `dirty`.
/// Throws ErrorCode::kToleranceNotMet where no count up to the cap holds them all.
Represented represent(std::size_t n_curves, const PointsOf& points_of,
                      const PositionsOf& positions_of, const std::vector<CurveFit>& fits,
                      int degree, bool periodic, const Point& bound, int threads,
                      bool shared_params, std::size_t max_points,
                      std::span<const double> shared_positions,
                      std::vector<Rerepresentation>* reuse, int reuse_count,
                      const std::vector<char>* dirty, bool weighted = false,
                      Resampling resampling = Resampling::kPaper);

}  // namespace sfit::detail
