// Corner knots (docs/method.md, "Corner knots"): beside the default fit, where the rows have
// corners matched across them (corner_rows.h), a surface on corner-aligned parameters with a
// degree-fold knot at each corner and uniform knots between; kept only when it has strictly
// fewer control points, holds T at every point, does not fold and stays calm between its
// rows. Private to the fit driver.
//
// PURPOSE  Cornered sections (ship stations, ducts, blunt edges) need as many control points
//          as points on uniform knots with per-row parameters; a crease at each corner and a
//          few control points per smooth stretch suffice once every row's k-th corner sits at
//          the same u.
// METHOD   1. Corners and parameters (corner_rows.h): u of each point its row's chord fraction
//             remapped so its k-th corner sits at U_k; v per row as the fit's. Closed rows
//             (closed_corners.h): each row counted from its seam, on a corner common to the
//             rows; u periodic, with a degree-fold knot at 0 (the seam) too.
//          2. u knots: a degree-fold knot at each U_k, s_k uniform spans in stretch k. From
//             s_k = 1, each row alone on them (least squares): a stretch where some row misses
//             kRowShare T gets more spans, until every row holds it.
//          3. v knots: uniform on the fit's v domain; the fewest nv whose tensor-product least
//             squares holds T at every point (bisection), more u spans where none does.
//          4. Each stretch's spans, then nv, lowered while T still holds.
//          A small second-difference term keeps every solve defined (adaptive_knots.h).
// LIMITS   An open v; the default method and parameter rule only (a rule or method asked for
//          keeps its own). Solves are bounded (kMaxSolves, kMaxWork); a closed u solves with
//          the cyclic band's dense tail (about twice the work of an open one).
#pragma once

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

/// Whether the corner knots run for these options (the default method and rule, an open v,
/// T > 0, no fixed counts).
bool corner_knots_apply(const FitOptions& options);

/// Replaces `result`'s surface, u, v and report (counts, deviations, fold, knots "corners",
/// parameters "chord") by the corner-knot surface when that is strictly smaller, holds T, does
/// not fold and stays calm between rows; true if it did. `rows` as the method fitted them
/// (aligned), `result` with u in their order; `threads` for the checks. The report's reason
/// says what replaced the search's surface; closed rows: the report's seams too, on `rows`
/// (restore_original_order() composes them with the alignment).
bool corner_knots(const Rows& rows, const FitOptions& options, int threads, FitResult& result);

}  // namespace sfit::detail
