// Seam alignment of closed rows and orientation of open rows (docs/seams.md): before the curve
// stage, each row's start point and direction are chosen to match its neighbour, so that
// sections which start anywhere and run either way round give the surface of sections that
// start at corresponding points. The seams move onto a point of the data's own (align_rows()).
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include "sfit/parametrization.h"
#include "sfit/rows.h"

namespace sfit {

/// Where closed rows start (FitOptions::seam).
enum class SeamMode {
  kAlign,  ///< default: each closed row starts where its neighbour starts (and runs its way)
  kKeep,   ///< rows start where they are given (the paper's scheme)
};
/// Which way open rows run (FitOptions::orient).
enum class OrientMode {
  kAuto,  ///< default: a row running against its neighbour is reversed
  kKeep,  ///< rows run as given
};

/// "align", "keep"; "auto", "keep".
std::string_view to_string(SeamMode m);
std::string_view to_string(OrientMode m);
/// The inverses of to_string(); false if `name` is none of them.
bool parse_seam_mode(std::string_view name, SeamMode& out);
bool parse_orient_mode(std::string_view name, OrientMode& out);

/// How one row was re-ordered: aligned point k is original point (shift + k) mod N, or
/// (shift - k) mod N when reversed. An open reversed row has shift N - 1.
/// `offset` (closed rows, -1 ... 1): the seam lies that fraction of a point spacing past
/// aligned point 0, in the aligned direction (the spacing to point 1, or for a negative offset
/// to point N-1); the fit gives the row's points positions measured from there, which is
/// exact for the original points, where a whole-index shift would twist ragged rows by up to
/// half a spacing.
struct RowSeam {
  long shift = 0;
  bool reversed = false;
  double offset = 0;
};

/// Original index of aligned point k of a row of n points.
inline std::size_t source_index(const RowSeam& s, std::size_t n, std::size_t k) {
  const long nn = static_cast<long>(n);
  long i = s.reversed ? s.shift - static_cast<long>(k % n) : s.shift + static_cast<long>(k % n);
  i %= nn;
  if (i < 0) i += nn;
  return static_cast<std::size_t>(i);
}

/// The re-ordering of every row.
struct RowAlignment {
  std::vector<RowSeam> rows;  ///< one per row
  bool identity() const {
    for (const RowSeam& s : rows)
      if (s.shift != 0 || s.reversed || s.offset != 0) return false;
    return true;
  }
};

/// Chooses each row's start and direction (closed rows: `seam` picks the start, `orient` the
/// direction; open rows: `orient` only). Row j is matched against row j-1 as aligned (rows of
/// fewer than 3 points, or whose points all coincide, are kept and skipped as references):
/// both are taken as curves through their points (cubic Hermite), sampled at 64 equal
/// fractions from their start and centred, and the start and direction minimising the sum of
/// squared distances between samples of equal fraction win, searched over every original
/// point as start and refined between its neighbours (RowSeam::offset). A row with as many
/// points as its reference keeps the reference's offset (the rows correspond point by point).
/// The given start is kept where the best lies within 1e-3 of a spacing of it. Then every
/// seam moves by the same fraction of its row's points onto a point of the data's own, so
/// that rotated and reversed copies of the rows get the same seams: the sharpest corner of any
/// row (a turn of more than 86 degrees, a trailing edge), else the first row's point farthest
/// from the centre of its bounding box (ties: the one nearest to a point of the next row, then
/// the row's first point, then the lexicographically smallest). The surface follows the first
/// row's direction. An open row is reversed when that halves the distance.
/// Fractions are those `rule` gives the points along the row (normalized_positions()): equal
/// steps in the point's index for the paper's rule, uniform and fewest (the paper's parameters
/// are, so the surface joins points of equal index fraction), chord-length or centripetal
/// fractions for those rules.
RowAlignment align_rows(const Rows& rows, bool closed_u, SeamMode seam, OrientMode orient,
                        Parametrization rule = Parametrization::kPaper);

/// The rows re-ordered by `a` (aligned point k of row j is original point
/// source_index(a.rows[j], N_j, k)).
Rows apply_alignment(const Rows& rows, const RowAlignment& a);

/// For every aligned point (in the order of apply_alignment(rows, a).points()), its index in
/// rows.points().
std::vector<std::size_t> original_indices(const Rows& rows, const RowAlignment& a);

}  // namespace sfit
