// Folds and other shape measures of a fitted surface (docs/seams.md): numbers that show a bad
// surface, one that doubles back on itself between the rows or swings away from the data,
// while every data point is within tolerance.
#pragma once

#include <span>

#include "sfit/rows.h"
#include "sfit/surface.h"

namespace sfit {

/// How far the surface doubles back between its rows: on dense samples u (8 per knot span
/// along u, at least 64, at most what 1e5 samples allow, at least 16) of every column v -> S(u, v),
/// each stretch between two consecutive rows' parameters v_j < v_{j+1} (and, closed across, from
/// the last row round to the first) is sampled 16 times and projected onto its own chord S(u,
/// v_{j+1}) - S(u, v_j); the fold is the largest distance a sample falls back behind the farthest
/// point reached before it, over the stretches where the normal S_u x S_v reverses between
/// consecutive samples (0: no fold). A column that turns round with the data (a spout's lip) turns
/// its normal smoothly and is no fold; one that doubles back on itself reverses it: the surface
/// overlaps itself there, meshes get flipped triangles, offsets and thickening fail. `v` holds each
/// row's parameter (FitResult::v).
double fold_measure(const Surface& s, std::span<const double> v);

struct ShapeMeasures {
  double fold = 0;           ///< fold_measure()
  double box_excursion = 0;  ///< largest distance of a sample outside the data's box
  /// Largest distance from the surface, sampled midway between consecutive rows (32 samples
  /// along u), to the nearer of the two data rows (as polylines, closed when closed_u; each
  /// searched within 1/32 of the row, at least 8 points, either side of the point whose
  /// parameter is nearest the sample's).
  double row_gap = 0;
};

/// The fold, the box excursion (on the fold's samples) and the gap between rows. The fold's
/// samples here stay within a quarter of the data's points (at least 2e4, at most 1e5).
/// `u` and `v` are the points' and rows' parameters (FitResult::u, ::v).
ShapeMeasures measure_shape(const Surface& s, const Rows& rows, std::span<const double> u,
                            std::span<const double> v, const BoundingBox& box, bool closed_u);

/// A fold above this fraction of the data's bounding-box diagonal counts as one (round-off
/// stays below 1e-12 of it on a surface that runs forwards).
inline constexpr double kFoldRelative = 1e-7;

}  // namespace sfit
