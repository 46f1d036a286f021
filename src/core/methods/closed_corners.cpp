#include "closed_corners.h"

#include <algorithm>
#include <cmath>

#include "between_rows.h"
#include "sfit/parametrization.h"

namespace sfit::detail {
namespace {

constexpr double kSeamReach = 0.12;  // seam corner beyond the nearest point, at most (row lengths)
constexpr double kMinShare = 0.5;    // rows with a seam corner, at least (as match_corners())
constexpr double kSeamGap = 0.01;    // another corner this near the seam is the seam (fraction)

double row_length(std::span<const Point> row) {
  double len = 0;
  for (std::size_t i = 0; i < row.size(); ++i) len += (row[(i + 1) % row.size()] - row[i]).norm();
  return len;
}

}  // namespace

MatchedCorners match_closed_corners(const Rows& rows,
                                    const std::vector<std::vector<RowCorner>>& corners) {
  MatchedCorners m;
  const std::size_t n = rows.size();
  if (n < 2 || corners.size() != n) return m;
  // 2. The seam: from the sharpest corner of all, outwards row by row.
  std::size_t first = n, first_corner = 0;
  double sharpest = 0;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t c = 0; c < corners[j].size(); ++c)
      if (corners[j][c].turn > sharpest) {
        sharpest = corners[j][c].turn;
        first = j;
        first_corner = c;
      }
  if (first == n) return m;
  std::vector<std::size_t> seam(n, 0);   // the seam's point (its corner's, or the nearest)
  std::vector<long> seam_corner(n, -1);  // which of the row's corners is its seam (-1: none)
  seam[first] = corners[first][first_corner].index;
  seam_corner[first] = static_cast<long>(first_corner);
  std::size_t with = 1;
  for (int dir : {1, -1}) {
    Point at = rows[first][seam[first]];
    for (long j = static_cast<long>(first) + dir; j >= 0 && j < static_cast<long>(n); j += dir) {
      const std::size_t r = static_cast<std::size_t>(j);
      const auto row = rows[r];
      // Within reach: at most kSeamReach of the row's length farther than its nearest point.
      double gap = 0;
      const std::size_t near = nearest_in_row(row, at, &gap);
      double best = std::sqrt(gap) + kSeamReach * row_length(row);
      for (std::size_t c = 0; c < corners[r].size(); ++c) {
        const double d = (row[corners[r][c].index] - at).norm();
        if (d <= best) {
          best = d;
          seam_corner[r] = static_cast<long>(c);
        }
      }
      if (seam_corner[r] >= 0) {
        seam[r] = corners[r][static_cast<std::size_t>(seam_corner[r])].index;
        ++with;
      } else {
        seam[r] = near;
      }
      at = row[seam[r]];
    }
  }
  if (static_cast<double>(with) < kMinShare * static_cast<double>(n)) return m;
  // 3. The other corners, counted from the seam, matched as an open row's.
  std::vector<std::vector<RowCorner>> rest(n);
  std::vector<double> seam_at(n, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    const double f0 = seam_corner[j] >= 0
                          ? corners[j][static_cast<std::size_t>(seam_corner[j])].fraction
                          : normalized_positions(rows[j], Parametrization::kChord, true)[seam[j]];
    seam_at[j] = f0;
    for (std::size_t c = 0; c < corners[j].size(); ++c) {
      if (static_cast<long>(c) == seam_corner[j]) continue;
      RowCorner k = corners[j][c];
      k.fraction -= f0;
      if (k.fraction < 0) k.fraction += 1;
      if (k.fraction > kSeamGap && k.fraction < 1 - kSeamGap) rest[j].push_back(k);
    }
    std::sort(rest[j].begin(), rest[j].end(),
              [](const RowCorner& a, const RowCorner& b) { return a.fraction < b.fraction; });
  }
  m = match_corners(rest);
  if (m.common.empty()) {  // nothing else consistent: the seam alone
    m.common.clear();
    m.fraction.assign(n, {});
  }
  m.seam = std::move(seam_at);
  return m;
}

}  // namespace sfit::detail
