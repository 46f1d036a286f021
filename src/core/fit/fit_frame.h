// The frame the fit methods share (private): validation is sfit::validate(); here the thread
// count, the data's box, the clock and the guards every candidate surface must pass.
#pragma once

#include <vector>

#include "deviation.h"
#include "sfit/fold_check.h"
#include "sfit/rows.h"
#include "sfit/surface.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

/// Threads for a fit of `rows`: 1 below 20000 points, else resolve_threads(requested).
int threads_for(const Rows& rows, int requested);
/// bounding_box() in fixed blocks (the same for any thread count).
BoundingBox box_of(const Rows& rows, int threads);
/// Seconds on the steady clock.
double now();
/// Whether the rows carry a weight other than 1 (unit weights fit as unweighted rows do, bit
/// for bit: docs/seams.md).
bool weights_matter(const Rows& rows);

/// The result every method returns, from its surface `s` made in centred coordinates (the rows
/// `centred`, the data moved by -`centre`): `s` moved back by `centre`, its parameters `u`
/// (per point) and `v` (per row), and `report` with the frame's part filled in: points, rows,
/// the tolerance of `o`, the final check `check`, the counts, degrees and closures, the
/// round-off allowance `roundoff` and the shape measures `shape` (measured by the method on
/// the centred surface). The method fills the rest of the report (its method, rule, timing).
FitResult frame_result(Surface s, std::vector<double> u, std::vector<double> v, FitReport report,
                       const DeviationCheck& check, const ShapeMeasures& shape, const Rows& centred,
                       const Point& centre, double roundoff, const FitOptions& o);

/// Whether a surface stays near its data between the points it was checked at: every control
/// point within the data's box grown by its diagonal, and the surface, sampled 4 times per
/// knot span each way, within the box grown by 1/10 of it.
bool stays_near_the_data(const Surface& s, const BoundingBox& box);

/// A check on a candidate surface beyond its data points (the final check covers those).
struct Guard {
  const char* name;
  bool (*check)(const Surface& s, const BoundingBox& box);
};
/// Runs every guard (fit_frame.cpp lists them) on `s` (in the coordinates of `box`); the name
/// of the first that fails, nullptr when all pass. Every method calls this on the surface it
/// would return and on every candidate it keeps.
const char* failed_guard(const Surface& s, const BoundingBox& box);

}  // namespace sfit::detail
