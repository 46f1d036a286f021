// What the rows need alone at T (docs/method.md 7.12): each row fitted as a curve at T, the
// test that says when T itself forces (near) interpolation, and the numbers a report gives
// where no surface below the points held. Private to the surface method.
#pragma once

#include <cstddef>
#include <string>

#include "sfit/options.h"
#include "sfit/rows.h"

namespace sfit::detail {

/// Rows fitted alone at T.
struct RowsAlone {
  long rows = 0;    // rows fitted (of those with more than degree + 1 points)
  long longer = 0;  // rows with more than degree + 1 points
  long need = 0;    // control points they need together (each at most its points)
  long have = 0;    // their points
  long full = 0;    // rows that need every point
  long most = 0;    // the most one row needs
};

/// Up to `picks` rows spread over the data, of those with more than degree + 1 points
/// (shorter ones are interpolated at any T), and the longest row where they miss it, each
/// fitted alone as a curve at T (chord-length
/// positions, count_floor.h's fit, the fast search; an axis with T = 0 at `roundoff`).
RowsAlone rows_alone(const Rows& centred, const FitOptions& o, double roundoff, std::size_t picks);

/// Whether T forces (near) interpolation: rows_alone() of 8 rows need together at least 90 %
/// of their points. `why` gets the numbers ("the rows fitted alone at T need a of their b
/// points"), or says that no row is long enough to tell (then false).
bool t_forces_interpolation(const Rows& centred, const FitOptions& o, double roundoff,
                            std::string& why);

/// For a report where no surface below the points held: what up to 256 rows spread over the
/// data need alone at T ("256 of the 681 rows ... fitted alone at T need a of their b points,
/// c of them every point, one row at most m control points"); empty where no row is longer
/// than degree + 1 points.
std::string rows_alone_note(const Rows& centred, const FitOptions& o, double roundoff);

}  // namespace sfit::detail
