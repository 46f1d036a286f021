#include "count_floor.h"

#include <algorithm>
#include <vector>

#include "deviation.h"
#include "fit_frame.h"
#include "parallel.h"
#include "sfit/curve_fit.h"

namespace sfit::detail {

namespace {
constexpr std::size_t kPicks = 8;

// The smallest count holding `points` at `bound` under `rule`, and whether it interpolates;
// 0 where the curve says nothing (too few points).
std::pair<int, bool> smallest_count(std::span<const Point> points, int degree, bool closed,
                                    Parametrization rule, const Point& bound) {
  const int n = static_cast<int>(points.size());
  if (n < degree + 2) return {0, false};
  CurveFitOptions c;
  c.degree = degree;
  c.periodic = closed;
  c.search = CountSearch::kFast;
  c.bound = bound;
  std::vector<double> positions;
  if (rule != Parametrization::kPaper) {
    positions = normalized_positions(points, rule, closed);
    c.positions = positions;
  }
  const CurveFit f = fit_curve(points, c);
  if (f.curve.control.empty()) return {0, false};
  return {f.curve.count(), f.curve.count() >= n};
}
}  // namespace

std::vector<std::size_t> spread_rows(const Rows& rows, const std::vector<std::size_t>& among,
                                     std::size_t picks) {
  std::vector<std::size_t> out;
  const std::size_t M = among.size(), spread = std::min(picks, M);
  if (spread == 0) return out;
  std::size_t longest = among[0];
  for (std::size_t i : among)
    if (rows[i].size() > rows[longest].size()) longest = i;
  bool has_longest = false;
  for (std::size_t k = 0; k < spread; ++k) {
    out.push_back(among[k * (M - 1) / std::max<std::size_t>(1, spread - 1)]);
    has_longest = has_longest || rows[out.back()].size() == rows[longest].size();
  }
  if (!has_longest) out.push_back(longest);
  return out;
}

CountFloor count_floor(const Rows& rows, const FitOptions& o, Parametrization rule, double roundoff,
                       FloorPart part) {
  CountFloor out{o.degree_u + 1, o.degree_v + 1, false};
  const std::size_t M = rows.size();
  if (M == 0 || weights_matter(rows)) return out;
  Point bound;
  for (int a = 0; a < 3; ++a) bound[a] = o.tolerance[a] > 0 ? o.tolerance[a] : roundoff;
  const std::size_t n = rows[0].size();
  bool grid = M >= static_cast<std::size_t>(o.degree_v) + 2;
  for (std::size_t j = 0; j < M && grid; ++j) grid = rows[j].size() == n;
  // The rows: up to kPicks spread over the data, and the longest row where they miss it
  // (spread_rows(); long_beside_short in bench/adversarial.py: 8 rows of 5, "forced", and the
  // floor nu 5 where the long row needs 93 at the paper's rule).
  std::vector<std::size_t> row_at;
  if (part != FloorPart::kColumns) {
    std::vector<std::size_t> all(M);
    for (std::size_t j = 0; j < M; ++j) all[j] = j;
    row_at = spread_rows(rows, all, kPicks);
  }
  const std::size_t row_picks = row_at.size();
  const std::size_t col_picks = grid && part != FloorPart::kRows ? std::min(kPicks, n) : 0;
  std::vector<std::pair<int, bool>> got(row_picks + col_picks, {0, false});
  parallel_for(got.size(), threads_for(rows, o.threads), [&](std::size_t k) {
    if (k < row_picks) {
      got[k] = smallest_count(rows[row_at[k]], o.degree_u, o.closed_u, rule, bound);
      return;
    }
    const std::size_t c = k - row_picks, i = c * (n - 1) / std::max<std::size_t>(1, col_picks - 1);
    std::vector<Point> column(M);
    for (std::size_t j = 0; j < M; ++j) column[j] = rows[j][i];
    got[k] = smallest_count(column, o.degree_v, o.closed_v, rule, bound);
  });
  out.forced = row_picks > 0;
  for (std::size_t k = 0; k < got.size(); ++k) {
    if (k < row_picks) {
      out.nu = std::max(out.nu, got[k].first);
      out.forced = out.forced && got[k].second;
    } else {
      out.nv = std::max(out.nv, got[k].first);
    }
  }
  return out;
}

// A lower bound on the two-stage fit's nu x nv at the paper's rule: its nu is at least every
// row's count, which is at least the smallest count holding that row within the curve
// stage's budget (CountSearch::kLinear), and its nv at least degree_v + 1. From 8 rows.
// Bounded: each row's scan tries at most kLowerBoundCounts counts (one O(points) solve each);
// where none holds, the count after the last one tried is the row's bound (every count below
// it failed). A row with one outlier needs thousands of counts: 2 rows of 30000 points took
// minutes at one solve per count, a fraction of a second now. Rows whose counts stay below
// degree + 1 + kLowerBoundCounts (every data set of the tests) get the same bound as before.
long sfit01_lower_bound(const Rows& rows, const FitOptions& o, long needed) {
  const double roundoff = kRoundoffRelative * bounding_box(rows).diagonal();
  CurveFitOptions co;
  co.degree = o.degree_u;
  co.periodic = o.closed_u;
  co.search = CountSearch::kLinear;
  // The scan need not pass the count whose bound reaches `needed`: a row that fails below it
  // already puts the bound there.
  const long want = (needed + o.degree_v) / (o.degree_v + 1) - (o.degree_u + 1);
  const int kLowerBoundCounts = static_cast<int>(std::clamp<long>(want, 1, 256));
  co.linear_limit = kLowerBoundCounts;
  for (int a = 0; a < 3; ++a)
    co.bound[a] = o.tolerance[a] > 0 ? std::max(0.5 * o.tolerance[a] * (1 - 1e-9), 0.5 * roundoff)
                                     : 0.5 * roundoff;
  const std::size_t M = rows.size(), picks = std::min<std::size_t>(8, M);
  std::vector<int> counts(picks, 0);
  parallel_for(picks, threads_for(rows, o.threads), [&](std::size_t p) {
    const auto row = rows[p * (M - 1) / std::max<std::size_t>(1, picks - 1)];
    if (row.size() >= static_cast<std::size_t>(o.degree_u + 1)) {
      const CurveFit f = fit_curve(row, co);
      counts[p] = f.curve.control.empty() ? o.degree_u + 1 + kLowerBoundCounts : f.curve.count();
    }
  });
  const int nu = std::max(o.degree_u + 1, *std::max_element(counts.begin(), counts.end()));
  return static_cast<long>(nu) * (o.degree_v + 1);
}

}  // namespace sfit::detail
