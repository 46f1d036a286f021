// The final check on the surface as it is returned and written: control points in the data's
// own coordinates (the centre added back), evaluated there against the data as given. The
// search and the stages judge candidates on centred data; at a large offset the centre's
// digits crowd out the shape's, and only this check sees what a reader of the file sees.
// Private.
#pragma once

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

/// The round-off allowance per axis: `roundoff` where that axis's tolerance is 0 (T = 0
/// asks for interpolation, which holds only up to round-off), 0 elsewhere: a tolerance > 0 is
/// held as given.
Point roundoff_allowance(const Point& tolerance, double roundoff);

/// Spacing of doubles at `x` (its unit in the last place), 0 at 0.
double double_spacing(double x);

/// Throws kInputData where the data's offset from the origin leaves doubles too coarse for the
/// tolerance on some axis: their spacing at the data's largest coordinate exceeds T (plus the
/// allowance at T = 0). `box` is the data's box, `roundoff` the absolute allowance.
void check_offset_digits(const BoundingBox& box, const Point& tolerance, double roundoff);

/// Replaces r's check (max deviation, worst point, within_tolerance) by the check of
/// r.surface exactly as it stands (the data's coordinates) against `rows` (as given, at r.u
/// and r.v_for_points()): a point holds where |S - D| plus a bound on the round-off of evaluating S
/// there (any evaluator, degree and control points' size) is within T (plus the allowance at T =
/// 0). Where the method's own check (r.report.within_tolerance) held and this one does not:
/// if the surface holds on the data less the box's centre, the offset took the digits: throws
/// kInputData, naming the point; else the method was wrong: within_tolerance false. It is the
/// driver's one final check (fit_driver.h) for every method. The verdict is the same for any thread
/// count.
void check_as_written(FitResult& r, const Rows& rows, const FitOptions& o);

}  // namespace sfit::detail
