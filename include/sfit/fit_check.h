// The library's final check of a fit, for a surface made or changed outside fit_surface() (a
// refit at frozen counts, a surface moved by hand): the same criterion every fit's report gets.
#pragma once

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit {

/// Checks fit.surface exactly as it stands (the control points as they would be written)
/// against `rows` at fit.u and fit.v_for_points(), and sets fit.report's max_deviation, worst
/// point and within_tolerance: a point holds where |S - D| plus a bound on the round-off of
/// evaluating S there (any evaluator) is within `tolerance` per axis (plus
/// fit.report.roundoff where an axis's tolerance is 0). The criterion of fit_surface()'s final
/// check; unlike a fit it never throws for the data's offset: a surface that cannot be shown
/// to hold there is reported not within. `threads` as FitOptions::threads (0: all cores); the
/// verdict does not depend on it.
void check_fit_as_written(FitResult& fit, const Rows& rows, const Point& tolerance,
                          int threads = 0);

}  // namespace sfit
