// Lower bounds on a surface's counts from a few rows and columns fitted as curves at the full
// T: where the noise forces (near) interpolation the surface search cannot beat the two
// stages, and is not run (surface_method.cpp, docs/control-points.md). Private.
#pragma once

#include <climits>
#include <cstddef>
#include <vector>

#include "sfit/parametrization.h"
#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

struct CountFloor {
  /// The largest of the smallest counts holding T (fit_curve(), CountSearch::kFast) of up to
  /// 8 rows spread over the data and the longest row (where they miss it): a surface restricted to
  /// a row is a curve on its u knots, so (least squares taken as the measure of what a count can
  /// hold) no surface with fewer control points along the rows holds there either. degree_u + 1
  /// where nothing is known.
  int nu = 0;
  /// The same across, from up to 8 columns where every row has as many points (a grid);
  /// degree_v + 1 otherwise.
  int nv = 0;
  /// Every sampled row needs a control point per point (interpolation). The longest row is
  /// among them, so short rows that need all their points because they are short (any row of
  /// degree + 2 points where the data is curved) do not make it true beside a long row.
  bool forced = false;
};

/// Which curves count_floor() fits: all, the rows only (nv stays degree_v + 1) or the columns
/// only (nu stays degree_u + 1, not forced). The rows' and the columns' parts are the same
/// numbers as in kAll (each curve is fitted alone), so a caller may fit the rows first and the
/// columns only where the rows do not decide already.
enum class FloorPart { kAll, kRows, kColumns };

/// The rows a test of what the rows need alone fits: up to `picks` of `among` (indices of
/// `rows`, in order) spread evenly over them, and the longest of `among` where those miss its
/// length. Rows of very different lengths say very different things: a row of 5 points beside
/// one of 3,000 needs its 5 at a T that the long row holds with 15 because it is short, not
/// because of noise, and without the longest row the picks can all be such rows.
std::vector<std::size_t> spread_rows(const Rows& rows, const std::vector<std::size_t>& among,
                                     std::size_t picks);

/// The floor of `rule` on `rows` (centred) at T = o.tolerance (the round-off where T is 0).
/// Weighted rows and rows shorter than degree + 2 points say nothing (the floor stays at
/// degree + 1, not forced). Counted work: a few curve solves per sampled row and column.
CountFloor count_floor(const Rows& rows, const FitOptions& o, Parametrization rule, double roundoff,
                       FloorPart part = FloorPart::kAll);

/// A lower bound on the two-stage fit's nu x nv at the paper's rule: its nu is at least every
/// row's count at the curve stage's budget T / 2, from 8 rows (surface_method.cpp defers the
/// two stages on large data while the search beats it).
/// Each row's scan stops at the count whose bound reaches `needed` (where the bound is to be
/// compared with a count of `needed`: the same verdict, fewer solves).
long sfit01_lower_bound(const Rows& rows, const FitOptions& o, long needed = LONG_MAX);

}  // namespace sfit::detail
