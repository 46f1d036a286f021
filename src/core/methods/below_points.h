// The surface search's last resort where its best surface has more control points than the data
// has points (docs/method.md 7.12): the geometric rule's scattered least squares with a calm
// term over the parts of the domain without data, at products nu x nv below the points,
// chosen by a bisection on the product; and the test that says when T itself forces
// (near) interpolation, so that no surface below the points can hold. Private to the surface
// method.
#pragma once

#include <optional>
#include <string>

#include "geometric_search.h"
#include "rows_alone.h"
#include "search_frame.h"

namespace sfit::detail {

/// The calm term's weight (relative, ScatteredProblem::solve()).
inline constexpr double kCalm = 1e-2;

/// The most flops of one factorisation the fallback solves (about half a second); larger pairs
/// are not tried.
inline constexpr double kBelowPointsCost = 1e9;

/// A surface of the geometric rule with fewer control points than `points` (the data's): nu x
/// nv by a bisection on the product (the ratio nu / nv from the data: the longest row's points
/// over the rows, then 1, then one control point across per row; never more than two across per
/// row), then one fewer along u or v while either holds, each pair solved with the calm term
/// (smoothness weights in between where the lowest one fails a guard), judged at every point
/// (T per axis), by the geometric rule's guard (stays_near_where_covered()) and unfolded
/// (geometric_fold()). Within a work budget in flops tied to the points: where it or the
/// descent's cap ends first, the result's stop reason says "below the points" without
/// "minimal". Where the largest products tried first all fail, a ladder of halved counts
/// along u and along v (largest product first) before giving up. Where nothing held from the
/// base plane's parameters, an open sheet's second pass (u warped by the rows' chord length,
/// where the first missed by at most 6x) and third (u and v stretched where the nearest pair
/// missed, below_points_dense.h, up to 3 rounds), in what is left of the budget. nullopt where none
/// held; `why` says what was tried. `work`: the budget in flops where > 0 (tests), else the default
/// (kWorkFloor or kWorkPerPoint a point, whichever is more).
std::optional<GeometricFit> fit_below_points(const Frame& fr, const FitOptions& o, long points,
                                             std::string& why, double work = 0);

/// Whether fit_below_points() takes the pair (nu, nv): solved from the same base fractions
/// with the calm term, corrected, T at every point, the guard passed and unfolded. Its result
/// is minimal by this: one fewer along u or along v does not hold (tested).
/// `warped`: from the fractions of the fallback's second pass (u warped by the rows' chord
/// length, warp_by_chord()), where the result's stop reason says so.
bool holds_below_points(const Frame& fr, const FitOptions& o, int nu, int nv, bool warped = false);

/// Where `r` (the search's result: the two stages' surface) has more control points than the
/// data has points, or folds (with the fold guard on), T is not 0 and the rule is sfit's to
/// choose (auto, fewest) or the geometric one (a rule the caller named is kept): unless T forces
/// interpolation (`forced`, or t_forces_interpolation()), fit_below_points()'s surface
/// replaces it (true); otherwise r's stop reason says which of the two kept it. With
/// `rows_tell` false the rows' need alone is not taken as T forcing interpolation (the
/// geometric rule was searched below a cap only, and its surfaces are no curves along rows):
/// the points against their neighbours' quadric are (neighbours_force_interpolation()).
bool replace_below_points(const Frame& fr, const FitOptions& o, bool forced, FitResult& r,
                          bool rows_tell = true);

}  // namespace sfit::detail
