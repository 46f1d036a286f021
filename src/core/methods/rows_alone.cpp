// What the rows need alone at T (rows_alone.h).
#include "rows_alone.h"

#include <algorithm>
#include <cmath>
#include <vector>

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
    CurveFitOptions c;
    c.degree = o.degree_u;
    c.periodic = o.closed_u;
    c.search = CountSearch::kFast;
    c.bound = bound;
    const std::vector<double> positions =
        normalized_positions(row, Parametrization::kChord, o.closed_u);
    c.positions = positions;
    const CurveFit f = fit_curve(row, c);
    need[k] = f.curve.control.empty() ? have[k] : std::min<long>(f.curve.count(), have[k]);
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
