#include "corner_rows.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "sfit/parametrization.h"

namespace sfit::detail {
namespace {

constexpr double kCornerWindow = 0.04;  // the window of arc length, a fraction of the row's
constexpr double kCornerAngle = 0.6;    // radians (34 degrees) of turning within the window
constexpr double kKinkAngle = 0.35;     // open rows: radians (20 degrees), a kink's least turning
constexpr double kKinkConcentration = 0.8;  // its turning within half the window, at least
constexpr double kGapParallel = 1e-12;      // open rows' gap legs: sin^2 below which parallel
constexpr double kGapSpacings = 2.0;        // a segment this many median spacings long: a gap
constexpr double kCornerOffset = 2.0;       // the corner's distance off the window's chord, in T
constexpr double kWindowInT = 8.0;          // the window, at least this many T (noise turns less)
constexpr double kMatchReach = 0.12;        // a corner's chord fraction off the mean, at most
constexpr double kNeighbourJump = 0.15;     // a corner's chord fraction between neighbour rows
constexpr double kMinShare = 0.5;           // rows with the common count, and with each corner
constexpr double kSharpWindow = 0.5;        // closed rows: the corner's turning within this share
constexpr double kSharpShare = 0.75;        // of the window, at least this share of the whole
constexpr double kParallel = 1e-6;          // sin^2 of the angle below which two lines are parallel

// The point at arc length t along the polyline `row` (cumulative lengths `s`; closed: s has
// the closing segment's end too, and t wraps around the length s.back()).
Point at_arc(std::span<const Point> row, const std::vector<double>& s, double t, bool closed) {
  const std::size_t n = row.size();
  if (closed) t -= s.back() * std::floor(t / s.back());
  const auto it = std::upper_bound(s.begin(), s.end(), t);
  const std::size_t i =
      std::clamp<std::size_t>(static_cast<std::size_t>(it - s.begin()), 1, s.size() - 1);
  const double d = s[i] - s[i - 1];
  const double a = d > 0 ? std::clamp((t - s[i - 1]) / d, 0.0, 1.0) : 0.0;
  return (1 - a) * row[i - 1] + a * row[i == n ? 0 : i];
}

// How far the row turns at point i between the chords from and to the points a window `w` of
// arc length before and after it (radians; 0 where the window leaves an open row). The
// windows wrap on a closed row.
double turn_at(std::span<const Point> row, const std::vector<double>& s, std::size_t i, double w,
               bool closed) {
  if (!closed && (s[i] - w < 0 || s[i] + w > s.back())) return 0;
  const Point d1 = row[i] - at_arc(row, s, s[i] - w, closed),
              d2 = at_arc(row, s, s[i] + w, closed) - row[i];
  const double n1 = d1.norm(), n2 = d2.norm();
  return n1 > 0 && n2 > 0 ? std::acos(std::clamp(d1.dot(d2) / (n1 * n2), -1.0, 1.0)) : 0.0;
}

// The parameters tp, tq of the closest points of the lines p + t dp and q + t dq; false where
// they are parallel within `parallel` (the sine squared of their angle).
bool closest_on_lines(const Point& p, const Point& dp, const Point& q, const Point& dq,
                      double parallel, double& tp, double& tq) {
  const Point r = p - q;
  const double aa = dp.dot(dp), ab = dp.dot(dq), bb = dq.dot(dq), ar = dp.dot(r), br = dq.dot(r);
  const double den = aa * bb - ab * ab;
  if (!(den > parallel * aa * bb)) return false;
  tp = (ab * br - bb * ar) / den;
  tq = (aa * br - ab * ar) / den;
  return true;
}

// Where on the row (arc length) its corner lies, the corner's sample at arc length s[at]. A
// sample on the corner is the corner. Where the corner fell into a gap of the row (a segment
// next to the sample at least kGapSpacings median spacings long), the sample found is one end
// of the gap: the legs, each the line through the gap's end and the point half a window
// beyond it, meet (in 3D, the middle of their closest points) at P, ahead of both ends, and
// the corner is put inside the gap in proportion to P's distance from its ends (of two gaps,
// the one P lies nearer). Without this a row puts its crease a sample early or late, at a u
// where the other rows are before or past their corner.
double corner_arc(std::span<const Point> row, const std::vector<double>& s, std::size_t at,
                  double w, double spacing) {
  double arc = s[at], nearest = std::numeric_limits<double>::infinity();
  auto try_gap = [&](std::size_t lo) {
    const std::size_t hi = lo + 1;
    if (s[hi] - s[lo] < kGapSpacings * spacing || s[lo] - 0.5 * w < 0 || s[hi] + 0.5 * w > s.back())
      return;
    const Point a0 = at_arc(row, s, s[lo] - 0.5 * w, false),
                b0 = at_arc(row, s, s[hi] + 0.5 * w, false);
    const Point da = row[lo] - a0, db = row[hi] - b0;
    double ta = 0, tb = 0;
    if (!closest_on_lines(a0, da, b0, db, kGapParallel, ta, tb)) return;  // no corner point
    if (!(ta >= 1 && tb >= 1)) return;  // P behind a gap's end: the legs do not meet in it
    const Point P = 0.5 * ((a0 + ta * da) + (b0 + tb * db));
    const double p0 = (P - row[lo]).norm(), p1 = (row[hi] - P).norm();
    const Point e = row[hi] - row[lo];
    const double off = (P - row[lo] - e * (P - row[lo]).dot(e) / e.dot(e)).norm();
    if (off < nearest) {
      nearest = off;
      arc = s[lo] + (s[hi] - s[lo]) * p0 / (p0 + p1);
    }
  };
  if (at > 0) try_gap(at - 1);
  if (at + 1 < row.size()) try_gap(at);
  return arc;
}

}  // namespace

std::vector<RowCorner> row_corners(std::span<const Point> row, const Point& tol, bool closed,
                                   bool between) {
  std::vector<RowCorner> out;
  const std::size_t n = row.size();
  if (n < 8 || !(tol.minCoeff() > 0)) return out;
  std::vector<double> s(closed ? n + 1 : n, 0.0);
  for (std::size_t i = 1; i < s.size(); ++i) s[i] = s[i - 1] + (row[i % n] - row[i - 1]).norm();
  const double len = s.back();
  if (!(len > 0)) return out;
  std::vector<double> step(n - 1);
  for (std::size_t i = 1; i < n; ++i) step[i - 1] = s[i] - s[i - 1];
  std::nth_element(step.begin(), step.begin() + step.size() / 2, step.end());
  const double spacing = step[step.size() / 2];  // the median (open rows' gaps)
  const double t = tol.maxCoeff();
  const double w = std::max(kCornerWindow * len, kWindowInT * t), off = kCornerOffset * t;
  if (closed && 2 * w >= len) return out;
  // Whether point i turns by the angle (and how far): its windows wrap on a closed row.
  auto turning = [&](std::size_t i, double& turn) {
    turn = 0;
    if (!closed && (s[i] - w < 0 || s[i] + w > len)) return false;
    const Point a = at_arc(row, s, s[i] - w, closed), b = at_arc(row, s, s[i] + w, closed);
    const Point d1 = row[i] - a, d2 = b - row[i], ab = b - a;
    const double n1 = d1.norm(), n2 = d2.norm();
    if (!(n1 > 0 && n2 > 0)) return false;
    turn = std::acos(std::clamp(d1.dot(d2) / (n1 * n2), -1.0, 1.0));
    const double nab = ab.norm();
    const double along = nab > 0 ? d1.dot(ab) / nab : 0.0;  // off the chord a-b: h
    const double h = std::sqrt(std::max(0.0, n1 * n1 - along * along));
    // On an open row a weaker turn is a corner too where it is a kink: it turns within half
    // the window nearly as much as within the whole (a smooth bend turns about half as much).
    if (!closed)
      return h >= off &&
             (turn >= kCornerAngle || (turn >= kKinkAngle && turn_at(row, s, i, 0.5 * w, false) >=
                                                                 kKinkConcentration * turn));
    if (!(turn >= kCornerAngle && h >= off)) return false;
    // A closed row's corner turns within half the window nearly as much (a smooth lobe turns in
    // proportion to the window: no crease goes there).
    return turn_at(row, s, i, kSharpWindow * w, true) >= kSharpShare * turn;
  };
  // Where a closed row's corner lies between its points: the lines from the window's ends
  // through the points either side of point i meet there (nearest to each other); its arc
  // length from point i - 1, within the two spacings around point i. A sharp corner between
  // samples, creased at a sample instead, leaves the sample off the far side's line.
  auto between_points = [&](std::size_t i) {
    const std::size_t before = (i + n - 1) % n, after = (i + 1) % n;
    const double s0 = i == 0 ? s[n - 1] - len : s[before], s1 = s[i + 1];
    const Point a = at_arc(row, s, s[i] - w, true), b = at_arc(row, s, s[i] + w, true);
    const Point p = row[before], q = row[after], d1 = p - a, d2 = b - q;
    double tp = 0, tq = 0;
    if (!closest_on_lines(p, d1, q, d2, kParallel, tp, tq)) return s[i];  // about parallel: keep
    const Point c = 0.5 * (p + d1 * tp + q + d2 * tq);
    const double at = std::clamp(s0 + (c - p).norm(), s0, s1);
    return at < 0 ? at + len : at >= len ? at - len : at;
  };
  // A closed row is walked from a point that does not turn, so no run straddles its start.
  std::size_t from = 1, steps = n - 2;
  if (closed) {
    double turn = 0;
    for (from = 0; from < n && turning(from, turn);) ++from;
    if (from == n) return out;  // turning everywhere: no corner stands out
    steps = n;
  }
  // Runs of points turning by the angle; one corner per run, at its largest turning.
  double best = 0;
  std::size_t at = 0;
  bool in_run = false;
  auto close_run = [&] {
    if (!in_run) return;
    in_run = false;
    const double arc =
        closed ? (between ? between_points(at) : s[at]) : corner_arc(row, s, at, w, spacing);
    const RowCorner c{arc / len, best, at};
    if (!out.empty() && std::abs(c.fraction - out.back().fraction) * len < w) {
      if (c.turn > out.back().turn) out.back() = c;  // two runs within a window: the sharper
    } else {
      out.push_back(c);
    }
  };
  for (std::size_t k = 0; k < steps; ++k) {
    const std::size_t i = (from + k) % n;
    double turn = 0;
    if (turning(i, turn)) {
      if (!in_run || turn > best) {
        best = turn;
        at = i;
      }
      in_run = true;
    } else {
      close_run();
    }
  }
  close_run();
  if (!closed) return out;
  std::sort(out.begin(), out.end(),
            [](const RowCorner& x, const RowCorner& y) { return x.fraction < y.fraction; });
  // The last and the first corner within a window across the start: the sharper.
  if (out.size() > 1 && (1 - out.back().fraction + out.front().fraction) * len < w) {
    if (out.back().turn > out.front().turn) out.front() = out.back();
    out.pop_back();
    std::sort(out.begin(), out.end(),
              [](const RowCorner& x, const RowCorner& y) { return x.fraction < y.fraction; });
  }
  return out;
}

MatchedCorners match_corners(const std::vector<std::vector<RowCorner>>& corners, bool follow) {
  MatchedCorners m;
  const std::size_t rows = corners.size();
  if (rows < 2) return m;
  // The common count: the one most rows have (the larger on a tie).
  std::map<std::size_t, std::size_t> tally;
  for (const auto& c : corners) ++tally[c.size()];
  std::size_t count = 0, most = 0;
  for (const auto& [k, t] : tally)
    if (t >= most) {
      count = k;
      most = t;
    }
  if (count == 0 || static_cast<double>(most) < kMinShare * static_cast<double>(rows)) return m;
  std::vector<double> mean(count, 0.0);
  for (const auto& c : corners)
    if (c.size() == count)
      for (std::size_t k = 0; k < count; ++k) mean[k] += c[k].fraction / static_cast<double>(most);
  // Each row's corners matched to the means, the sharpest first: each to the mean nearest it
  // within reach that no sharper corner of the row took (a row's extra corners stay
  // unmatched). Taking the means in order once gave a row lacking its first corner the second
  // as its first; taking the nearest corner gave a weak chine the knuckle's place beside it.
  std::vector<std::vector<double>> f(rows, std::vector<double>(count, -1.0));
  std::vector<std::size_t> found(count, 0);
  std::vector<std::vector<bool>> taken(rows);
  for (std::size_t j = 0; j < rows; ++j) {
    taken[j].assign(corners[j].size(), false);
    std::vector<std::size_t> order(corners[j].size());
    for (std::size_t c = 0; c < order.size(); ++c) order[c] = c;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return corners[j][a].turn > corners[j][b].turn;
    });
    for (std::size_t c : order) {
      std::size_t pick = count;
      double gap = kMatchReach;
      for (std::size_t k = 0; k < count; ++k) {
        const double d = std::abs(corners[j][c].fraction - mean[k]);
        if (f[j][k] < 0 && d <= gap) {
          gap = d;
          pick = k;
        }
      }
      if (pick == count) continue;
      f[j][pick] = corners[j][c].fraction;
      taken[j][c] = true;
      ++found[pick];
    }
  }
  // Corners that move along the rows (a hull's chine rising towards the bow) leave the mean's
  // reach: a row's corner k not yet found is then its untaken corner nearest the corner k of
  // the nearest row that has it, within kNeighbourJump and in order, row after row.
  bool followed = false;
  for (bool grew = follow; grew;) {
    grew = false;
    for (std::size_t k = 0; k < count; ++k)
      for (std::size_t j = 0; j < rows; ++j) {
        if (f[j][k] >= 0) continue;
        double near = -1;
        for (std::size_t d = 1; d < rows && near < 0; ++d) {
          if (j >= d && f[j - d][k] >= 0)
            near = f[j - d][k];
          else if (j + d < rows && f[j + d][k] >= 0)
            near = f[j + d][k];
        }
        if (near < 0) continue;
        double lo = 0, hi = 1;
        for (std::size_t i = 0; i < count; ++i)
          if (f[j][i] >= 0)
            (i < k ? lo : hi) = i < k ? std::max(lo, f[j][i]) : std::min(hi, f[j][i]);
        std::size_t pick = corners[j].size();
        double gap = kNeighbourJump;
        for (std::size_t c = 0; c < corners[j].size(); ++c) {
          const double x = corners[j][c].fraction, d = std::abs(x - near);
          if (!taken[j][c] && x > lo && x < hi && d <= gap) {
            gap = d;
            pick = c;
          }
        }
        if (pick == corners[j].size()) continue;
        f[j][k] = corners[j][pick].fraction;
        taken[j][pick] = true;
        ++found[k];
        grew = followed = true;
      }
  }
  for (std::size_t k = 0; k < count; ++k)
    if (static_cast<double>(found[k]) < kMinShare * static_cast<double>(rows)) return m;
  // A corner a row lacks: interpolated between the nearest rows that have it (in row order).
  for (std::size_t k = 0; k < count; ++k)
    for (std::size_t j = 0; j < rows; ++j) {
      if (f[j][k] >= 0) continue;
      long lo = static_cast<long>(j) - 1, hi = static_cast<long>(j) + 1;
      while (lo >= 0 && f[static_cast<std::size_t>(lo)][k] < 0) --lo;
      while (hi < static_cast<long>(rows) && f[static_cast<std::size_t>(hi)][k] < 0) ++hi;
      const bool has_lo = lo >= 0, has_hi = hi < static_cast<long>(rows);
      // (A run of rows lacking it: each row reads the one filled before it, on the same line.)
      double v = 0;
      if (has_lo && has_hi) {
        const double a =
            static_cast<double>(static_cast<long>(j) - lo) / static_cast<double>(hi - lo);
        v = (1 - a) * f[static_cast<std::size_t>(lo)][k] + a * f[static_cast<std::size_t>(hi)][k];
      } else {
        v = f[static_cast<std::size_t>(has_lo ? lo : hi)][k];
      }
      f[j][k] = v;
    }
  // Consistency: ascending in every row, inside (0, 1), calm between neighbouring rows.
  for (std::size_t j = 0; j < rows; ++j)
    for (std::size_t k = 0; k < count; ++k) {
      const double lo = k == 0 ? 0.0 : f[j][k - 1];
      if (!(f[j][k] > lo + 0.01 && f[j][k] < 0.99)) return m;
      if (j > 0 && std::abs(f[j][k] - f[j - 1][k]) > kNeighbourJump) return m;
    }
  m.common.assign(count, 0.0);
  for (std::size_t k = 0; k < count; ++k) {
    for (std::size_t j = 0; j < rows; ++j) m.common[k] += f[j][k];
    m.common[k] /= static_cast<double>(rows);
  }
  m.fraction = std::move(f);
  m.followed = followed;
  return m;
}

std::vector<double> corner_parameters(const Rows& rows, const MatchedCorners& m) {
  std::vector<double> u;
  u.reserve(rows.total_points());
  const std::size_t count = m.common.size();
  const bool closed = !m.seam.empty();
  std::vector<double> x(count + 2), y(count + 2);
  x.front() = y.front() = 0;
  x.back() = y.back() = 1;
  for (std::size_t k = 0; k < count; ++k) y[k + 1] = m.common[k];
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (std::size_t k = 0; k < count; ++k) x[k + 1] = m.fraction[j][k];
    std::vector<double> f = normalized_positions(rows[j], Parametrization::kChord, closed);
    if (closed) {  // counted from the seam (its corner, between two points or at one)
      const double f0 = m.seam[j];
      for (double& t : f) t = t >= f0 ? t - f0 : std::min(1.0, t - f0 + 1);
    }
    for (double t : f) {
      const auto it = std::upper_bound(x.begin() + 1, x.end() - 1, t);
      const std::size_t i = static_cast<std::size_t>(it - x.begin());
      const double a = std::clamp((t - x[i - 1]) / (x[i] - x[i - 1]), 0.0, 1.0);
      u.push_back((1 - a) * y[i - 1] + a * y[i]);
    }
  }
  return u;
}

}  // namespace sfit::detail
