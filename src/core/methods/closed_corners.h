// The corners of closed rows matched across the rows (docs/method.md, "Corner knots"): the
// first step of the corner knots (corner_knots.h) where u is closed. Private.
//
// PURPOSE  Closed sections with corners (blades with a blunt or sharp trailing edge, ducts)
//          put their corners at a different place in every row; a closed surface with a crease
//          at each needs the k-th corner of every row at one u, and a seam somewhere.
// METHOD   1. Each row's corners, its windows wrapping around (row_corners(), closed), at
//             their points or between points (corner_knots() fits both, keeps the smaller).
//          2. The seam: on a common corner. The sharpest corner of all rows starts it; from
//             that row outwards, each row's seam is its corner nearest (in space) to the
//             previous row's seam, within kSeamReach of the row's length; a row with none
//             there takes its point nearest the previous seam (a rounded corner, or none).
//             Too few rows with a seam corner: no corners.
//          3. Each row counted from its seam: its other corners' fractions from the seam
//             point, matched across the rows as open rows' are (match_corners()); where they
//             match nothing consistent, the seam is the only corner.
// LIMITS   One seam corner common to half the rows at least; the rows' order and direction
//          as aligned by the driver (seam_alignment.h) for the other corners' order.
#pragma once

#include <vector>

#include "corner_rows.h"
#include "sfit/rows.h"

namespace sfit::detail {

/// Matches the corners of closed rows (row_corners(row, tol, true) of each): seam set, the
/// other corners as fraction and common; empty when too few rows share a seam corner.
MatchedCorners match_closed_corners(const Rows& rows,
                                    const std::vector<std::vector<RowCorner>>& corners);

}  // namespace sfit::detail
