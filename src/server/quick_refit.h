// The options of the quick refit that follows a drag (docs/method.md, "Editing the data": a quick
// image first, refined when the hand rests). One function, so the quick method can change in one
// place.
#pragma once

#include "sfit/surface_fit.h"

namespace sfit::server {

/// Options for refitting at the counts of `last` (the last full fit's report), with the
/// parameter rule that fit chose: where the surface search made it, its pair (nu, nv) solved
/// once by least squares (FitOptions::counts, FitNorm::kL2; the result may miss T and says
/// so); where the two stages made it, their row and column counts taken as the answer (one
/// solve per curve; a count that does not hold is searched as kFast).
FitOptions quick_refit_options(const FitOptions& full, const FitReport& last);

}  // namespace sfit::server
