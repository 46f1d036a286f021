// Whether a surface stays between its rows (docs/method.md 7.9): where each point has its
// own parameters (the geometric rule), a surface can hold every point and still swing far
// away between two neighbouring rows, using the small spread of a row's parameters across the
// rows to shape the row (ship stations 2.6 m apart: 4 x 193 control points whose columns swing
// 11 m between every two stations). Private to the surface search.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "sfit/rows.h"
#include "sfit/surface.h"

namespace sfit::detail {

/// Neighbouring points of consecutive rows: up to 16 points spread along each row and, for
/// each, the nearest point of the next row (closed across: the last row's next is the first),
/// as indices into the rows' points, with their rows and their distance.
struct RowPairs {
  std::vector<std::array<std::size_t, 2>> points;
  std::vector<std::array<std::size_t, 2>> rows;
  std::vector<double> gap;
};

/// The index of the point of `row` (not empty) nearest `q`, and its squared distance.
std::size_t nearest_in_row(std::span<const Point> row, const Point& q, double* squared = nullptr);

RowPairs row_pairs(const Rows& rows, bool closed_v);

/// The largest distance of the surface at each pair's middle parameters (u wrapped on a closed
/// surface) from the middle of the pair's two points, over the pair's gap plus 2 `t` (the
/// largest per-axis tolerance): about 1/2 or less on a surface that runs calmly between its
/// rows (at most 1.14 over the example sets and generated scan data), 4 on the swinging ship
/// stations above. `u`, `v`: the points' parameters (v per point, or per row).
double between_rows_ratio(const Surface& s, const Rows& rows, const RowPairs& pairs,
                          std::span<const double> u, std::span<const double> v, double t);

/// A surface whose between_rows_ratio() is above this swings away between its rows.
inline constexpr double kBetweenRowsLimit = 2.0;

}  // namespace sfit::detail
