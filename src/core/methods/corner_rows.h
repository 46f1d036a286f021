// The corners of rows and their matching across the rows (docs/method.md, "Corner knots"):
// the first step of the corner knots (corner_knots.h). Private.
//
// PURPOSE  Sections with sharp or rounded corners (ship stations: chine, knuckle, deck corner;
//          ducts; blunt trailing edges) put their corners at a different u in every row under
//          the per-row rules (index, chord), so no common knot can sit on them.
// METHOD   1. A row's corners: at each point, the turning between the chords to the points one
//             window of arc length before and after (the window a fraction of the row's
//             length, so a fillet shorter than the window turns within it); a corner where it
//             turns by kCornerAngle or more and the point lies off the chord between those two
//             by several T (noise within T is no corner); one corner per run of such points, at
//             its largest turning.
//          2. Matching: the corner count most rows have is the count; each row's corners are
//             matched in order to the mean chord fractions of the rows that have that count; a
//             corner a row lacks gets the fraction interpolated from the nearest rows that have
//             it. No consistent matching (too few rows with the count, a corner in too few
//             rows, a jump between neighbours): no corners.
//          3. Parameters: each row's chord fractions remapped piecewise linearly so its k-th
//             corner sits at U_k, the mean of the rows' k-th corner fractions.
// LIMITS   Corners within one window of an open row's ends are not looked for (the ends are
//          creases already); on a closed row the windows wrap around. Closed rows are matched
//          by closed_corners.h (a seam at a common corner), then here.
#pragma once

#include <span>
#include <vector>

#include "sfit/rows.h"

namespace sfit::detail {

/// One corner of a row: its chord fraction (0 ... 1), how far it turns (radians), its point
/// (the sharpest turning).
struct RowCorner {
  double fraction = 0;
  double turn = 0;
  std::size_t index = 0;
};

/// The corners of a row (chord fractions ascending), at per-axis tolerance `tol`; `closed`:
/// the row closes from its last point to its first (fractions of the closed length, the
/// windows wrapping around); `between` (closed rows): each corner's fraction where the lines
/// either side of its point meet, between two points (a sharp corner between samples), else
/// its point's.
std::vector<RowCorner> row_corners(std::span<const Point> row, const Point& tol,
                                   bool closed = false, bool between = false);

/// Matched corners: fraction[j][k] is row j's k-th corner (detected or interpolated),
/// common[k] = U_k their mean; empty when the rows have no consistent corners. Closed rows
/// (closed_corners.h): seam[j] is row j's chord fraction (of its closed length) at u = 0 (its
/// seam corner, every other fraction counted from it), and common may be empty (the seam the only
/// corner).
struct MatchedCorners {
  std::vector<std::vector<double>> fraction;
  std::vector<double> common;
  std::vector<double> seam;
  bool followed = false;  // some corner was found by following it from row to row
  bool empty() const { return common.empty() && seam.empty(); }
};

/// Matches the corners of every row (row_corners() of each) across the rows; with `follow`,
/// a corner beyond the mean's reach is also followed from the nearest row that has it.
MatchedCorners match_corners(const std::vector<std::vector<RowCorner>>& corners,
                             bool follow = true);

/// Each point's parameter in [0, 1]: its row's chord fraction (closed: of the closed length,
/// counted from the seam), remapped piecewise linearly so that the row's k-th corner sits at
/// m.common[k] (order of rows.points()).
std::vector<double> corner_parameters(const Rows& rows, const MatchedCorners& m);

}  // namespace sfit::detail
