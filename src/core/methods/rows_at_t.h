// The two stages with all of T for the rows and columns that interpolate their control points
// (FitSpec::rows_take_all, docs/method.md 7.2): the default's last try where no pair of the
// search beat the two stages and theirs has more control points than points. The two-stage
// method is the registry's "sfit01" (fit_registry.h), run on the driver's rows and centring.
// Private to the surface search (surface_method.cpp).
#pragma once

#include <optional>

#include "count_floor.h"
#include "fit_driver.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

/// The two stages (`two_stage`: the options of the two-stage fit `halves` was made with) run
/// again on `spec`'s rows and centring (the driver's) with the rows at all of T, where that
/// can leave a tenth to gain: its count is estimated as halves' nu scaled by the sampled rows'
/// counts at T (`floor_at_t`, count_floor.h) over those at T/2, times one per row across.
/// Returns the surface where it has fewer control points than `halves`, holds T and (with
/// search.fold_guard) does not fold; nullopt otherwise, and where a re-representation cannot
/// hold T.
std::optional<FitResult> fit_rows_at_t(const FitSpec& spec, const FitOptions& two_stage,
                                       const FitOptions& search, const FitResult& halves,
                                       const CountFloor& floor_at_t);

}  // namespace sfit::detail
