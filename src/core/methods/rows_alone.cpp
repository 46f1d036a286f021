// What the rows need alone at T (rows_alone.h).
#include "rows_alone.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "corner_rows.h"
#include "count_floor.h"
#include "fit_frame.h"
#include "geometric_params.h"
#include "parallel.h"
#include "sfit/curve_fit.h"

namespace sfit::detail {

namespace {

// Share of the points the rows alone must need for T to force (near) interpolation.
constexpr double kNearInterpolation = 0.9;
// Rows the forcing test fits, and rows a report's note fits.
constexpr std::size_t kForcingRows = 8;
constexpr std::size_t kNoteRows = 256;

// The control points one row alone needs at `bound`: the curve fitted at chord positions; an
// open row with corners (corner_rows.h) is fitted in pieces between them, a crease at each, so
// that a sharp corner, which no smooth curve on uniform knots follows, does not read as noise
// (hull stations at 1e-4 once claimed "T forces interpolation": 2,010 of 2,105 points).
long row_need(std::span<const Point> row, const FitOptions& o, const Point& bound) {
  auto fit = [&](std::span<const Point> piece) {
    const long n = static_cast<long>(piece.size());
    if (n <= o.degree_u + 1) return n;
    CurveFitOptions c;
    c.degree = o.degree_u;
    c.periodic = o.closed_u;
    c.search = CountSearch::kFast;
    c.bound = bound;
    const std::vector<double> positions =
        normalized_positions(piece, Parametrization::kChord, o.closed_u);
    c.positions = positions;
    const CurveFit f = fit_curve(piece, c);
    return f.curve.control.empty() ? n : std::min<long>(f.curve.count(), n);
  };
  const std::vector<RowCorner> corners =
      o.closed_u ? std::vector<RowCorner>{} : row_corners(row, bound);
  if (corners.empty()) return fit(row);
  // The pieces: the points up to each corner (a sample on the corner ends one piece and
  // starts the next); neighbouring pieces share the crease's control point.
  std::vector<double> s(row.size(), 0.0);
  for (std::size_t i = 1; i < row.size(); ++i) s[i] = s[i - 1] + (row[i] - row[i - 1]).norm();
  long need = 0;
  std::size_t first = 0;
  for (std::size_t k = 0; k <= corners.size() && first < row.size(); ++k) {
    const double at = k < corners.size() ? corners[k].fraction * s.back()
                                         : std::numeric_limits<double>::infinity();
    std::size_t last = first;
    while (last + 1 < row.size() && s[last + 1] <= at) ++last;
    need += fit(row.subspan(first, last - first + 1)) - (k > 0 ? 1 : 0);
    first = s[last] < at ? last + 1 : last;
  }
  return need;
}

}  // namespace

RowsAlone rows_alone(const Rows& centred, const FitOptions& o, double roundoff,
                     std::size_t picks_most) {
  // A row of at most degree + 1 points is interpolated by any count: it says nothing about
  // noise (60 rows of 2 points each on a smooth sheet once read as "T forces it"). Only the
  // longer rows are sampled.
  std::vector<std::size_t> longer;
  for (std::size_t i = 0; i < centred.size(); ++i)
    if (centred[i].size() >= static_cast<std::size_t>(o.degree_u) + 2) longer.push_back(i);
  const std::size_t M = longer.size(), picks = std::min<std::size_t>(picks_most, M);
  RowsAlone r;
  r.longer = static_cast<long>(M);
  if (picks == 0) return r;
  // The rows fitted: `picks` spread over the longer ones, and the longest where they miss it
  // (count_floor.h's spread_rows(): 8 rows of 5 points beside one of 300 once read as "T
  // forces interpolation", 40 of 40 points).
  const std::vector<std::size_t> chosen = spread_rows(centred, longer, picks);
  const std::size_t fitted = chosen.size();
  r.rows = static_cast<long>(fitted);
  Point bound;
  for (int a = 0; a < 3; ++a) bound[a] = o.tolerance[a] > 0 ? o.tolerance[a] : roundoff;
  std::vector<long> need(fitted, 0), have(fitted, 0);
  parallel_for(fitted, threads_for(centred, o.threads), [&](std::size_t k) {
    const auto row = centred[chosen[k]];
    have[k] = static_cast<long>(row.size());
    need[k] = std::min(have[k], row_need(row, o, bound));
  });
  for (std::size_t k = 0; k < fitted; ++k) {
    r.need += need[k];
    r.have += have[k];
    r.full += need[k] >= have[k] ? 1 : 0;
    r.most = std::max(r.most, need[k]);
  }
  return r;
}

bool t_forces_interpolation(const Rows& centred, const FitOptions& o, double roundoff,
                            std::string& why) {
  const RowsAlone r = rows_alone(centred, o, roundoff, kForcingRows);
  // Where no row is longer than degree + 1 points, nothing shows that T forces interpolation.
  if (r.rows == 0) {
    why =
        "every row has at most degree + 1 points, which any count interpolates: the rows "
        "alone say nothing about noise";
    return false;
  }
  why = "the rows fitted alone at T need " + std::to_string(r.need) + " of their " +
        std::to_string(r.have) + " points";
  return static_cast<double>(r.need) >= kNearInterpolation * static_cast<double>(r.have);
}

std::string rows_alone_note(const Rows& centred, const FitOptions& o, double roundoff) {
  const RowsAlone r = rows_alone(centred, o, roundoff, kNoteRows);
  if (r.rows == 0) return {};
  const long percent = std::lround(100.0 * r.need / static_cast<double>(r.have));
  return (r.rows == r.longer
              ? "all " + std::to_string(r.rows) + " rows"
              : std::to_string(r.rows) + " of the " + std::to_string(r.longer) + " rows") +
         " longer than degree + 1 points fitted alone at T need " + std::to_string(r.need) +
         " of their " + std::to_string(r.have) + " points (" + std::to_string(percent) + " %), " +
         std::to_string(r.full) + " of them every point, the most demanding " +
         std::to_string(r.most) + " control points";
}

}  // namespace sfit::detail
