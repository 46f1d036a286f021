// The two stages with all of T for the rows and columns that interpolate their control points
// (SurfaceFitter::rows_take_all(), docs/method.md 7.2): the default's last try where no pair of
// the search beat the two stages and theirs has more control points than points. Private to
// the surface search (surface_method.cpp).
#pragma once

#include <optional>
#include <span>

#include "count_floor.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

/// The two stages (`two_stage`: the options of the two-stage fit `halves` was made with) run
/// again with the rows at all of T, where that can leave a tenth to gain: its count is estimated
/// as halves' nu scaled by the sampled rows' counts at T (`floor_at_t`, count_floor.h) over
/// those at T/2, times one per row across. Returns the surface where it has fewer control
/// points than `halves`, holds T and (with o.fold_guard) does not fold; nullopt otherwise,
/// and where a re-representation cannot hold T.
std::optional<FitResult> fit_rows_at_t(const Rows& rows, const Rows& centred,
                                       const FitOptions& two_stage, const FitOptions& search,
                                       const FitResult& halves, const CountFloor& floor_at_t,
                                       double roundoff, double diagonal,
                                       std::span<const double> seam_offsets);

}  // namespace sfit::detail
