#include "row_matching.h"

#include <limits>
#include <tuple>

namespace sfit::detail::row_match {
namespace {

constexpr int kSamples = 64;          // equal arc-length samples compared per row
constexpr double kKeepSlack = 1.02;   // the given direction wins unless 2 % worse than the other
constexpr double kKeepOffset = 1e-3;  // the given start wins within this fraction of a spacing
constexpr double kTie = 1e-9;         // distances this close (relative) are equal
constexpr std::size_t kTieWork = 1 << 22;  // distances compared to break ties, at most
constexpr int kGoldenSteps = 56;           // a bracket of 2 spacings to 4e-12 of one

// The distance between positions a and b of a closed row (wrapped, 0 ... 1/2).
double wrapped(double a, double b) {
  double d = a - b;
  return std::fabs(d - std::floor(d + 0.5));
}

// The position of the seam `offset` point spacings past point i of closed row `line`, in the
// aligned direction (RowSeam::offset).
double position_of(const Polyline& line, std::size_t i, double offset, bool reversed) {
  const std::size_t n = line.p.size();
  const double next = line.at[i + 1] - line.at[i];
  const double prev = line.at[i] - (i > 0 ? line.at[i - 1] : line.at[n - 1] - 1.0);
  const double ahead = offset * ((offset >= 0) == !reversed ? next : prev);
  return reversed ? line.at[i] - ahead : line.at[i] + ahead;
}

RowSeam seam_at(const Polyline& line, double s, bool reversed);

}  // namespace

bool usable(std::span<const Point> row) {
  if (row.size() < 3) return false;
  for (const Point& q : row)
    if (q != row[0]) return true;
  return false;
}

// Samples of `line` at kSamples equal fractions starting at arc length `start`, going
// forwards or backwards (closed), or over the whole open row; centred on their mean.
std::vector<Point> samples(const Polyline& line, double start, bool backwards) {
  std::vector<Point> s(kSamples);
  const double step = line.closed ? line.total / kSamples : line.total / (kSamples - 1);
  Point mean = Point::Zero();
  for (int k = 0; k < kSamples; ++k) {
    const double d = step * k;
    s[k] = line.closed ? line(backwards ? start - d : start + d)
                       : line(backwards ? line.total - d : d);
    mean += s[k];
  }
  mean /= kSamples;
  for (Point& q : s) q -= mean;
  return s;
}

double cost(const std::vector<Point>& a, const std::vector<Point>& b) {
  double c = 0;
  for (int k = 0; k < kSamples; ++k) c += (a[k] - b[k]).squaredNorm();
  return c;
}

// `follow`: the row has as many points as the reference row, whose seam lies *follow point
// spacings past its first point; this row's seam then lies as far past one of its points.
Choice align_closed(const Polyline& line, const std::vector<Point>& ref, bool shifts,
                    bool directions, const double* follow) {
  const std::size_t n = line.p.size();
  const double keep = cost(samples(line, 0.0, false), ref);
  // Coarse: cyclic shifts of the row's own samples, both ways.
  const std::vector<Point> own = samples(line, 0.0, false);
  double best_coarse = std::numeric_limits<double>::infinity();
  int coarse_shift = 0;
  bool coarse_back = false;
  for (int back = 0; back < (directions ? 2 : 1); ++back)
    for (int c = 0; c < (shifts ? kSamples : 1); ++c) {
      double sum = 0;
      for (int k = 0; k < kSamples && sum < best_coarse; ++k) {
        const int m = back ? ((c - k) % kSamples + kSamples) % kSamples : (c + k) % kSamples;
        sum += (own[m] - ref[k]).squaredNorm();
      }
      if (sum < best_coarse) {
        best_coarse = sum;
        coarse_shift = c;
        coarse_back = back != 0;
      }
    }
  // Fine: every original point within 1.5 coarse steps of the coarse start, and the points
  // on either side of it (a row of fewer points than samples), that direction.
  const double centre = line.total * coarse_shift / kSamples;
  const double reach = 1.5 * line.total / kSamples;
  RowSeam best;
  double best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const double next = line.at[i + 1] - line.at[i];
    const double prev = line.at[i] - (i > 0 ? line.at[i - 1] : line.at[n - 1] - 1.0);
    if (shifts ? wrapped(line.at[i], centre) > std::max({reach, next, prev}) : i != 0) continue;
    const double c = cost(samples(line, line.at[i], coarse_back), ref);
    if (c < best_cost) {
      best_cost = c;
      best = RowSeam{static_cast<long>(i), coarse_back};
    }
  }
  if (!shifts) {
    // The direction only: the given one unless the other is better by more than 2 %.
    if (!(keep > kKeepSlack * best_cost)) return Choice{};
    return Choice{best, 0.0};
  }
  // A fractional start between the neighbouring points (golden section on the cost).
  const std::size_t i = static_cast<std::size_t>(best.shift);
  double s = line.at[i];
  {
    const double before =
        line.at[i] - (i == 0 ? line.at[n] - line.at[n - 1] : line.at[i] - line.at[i - 1]);
    const double after = line.at[i + 1];
    auto at = [&](double x) { return cost(samples(line, x, best.reversed), ref); };
    double a = before, b = after;
    constexpr double g = 0.6180339887498949;
    double x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = at(x1), f2 = at(x2);
    for (int it = 0; it < kGoldenSteps; ++it) {
      if (f1 < f2) {
        b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = at(x1);
      } else {
        a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = at(x2);
      }
    }
    if (std::min(f1, f2) < best_cost) s = f1 < f2 ? x1 : x2;
  }
  RowSeam seam = seam_at(line, s, best.reversed);
  if (follow) {
    // Rows of equal counts correspond point by point (sections from one sampling): the seam
    // keeps the reference row's fraction of a spacing, past the point that puts it nearest.
    RowSeam pick = seam;
    double d_best = 2;
    for (long k : {seam.shift - 1, seam.shift, seam.shift + 1}) {
      const std::size_t kk = static_cast<std::size_t>((k % static_cast<long>(n) + n) % n);
      const double d = wrapped(position_of(line, kk, *follow, best.reversed), s);
      if (d < d_best) d_best = d, pick = RowSeam{static_cast<long>(kk), best.reversed, *follow};
    }
    seam = pick;
  }
  // The given start and direction stay where the best start is within a small fraction of a
  // spacing of them, so rows that already correspond are fitted bit for bit as before.
  if (seam.shift == 0 && !seam.reversed && std::fabs(seam.offset) < kKeepOffset) return Choice{};
  return Choice{
      seam, position_of(line, static_cast<std::size_t>(seam.shift), seam.offset, seam.reversed)};
}

Corner sharpest(const Polyline& line) {
  Corner c;
  const std::size_t n = line.p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point a = line.p[i] - line.p[(i + n - 1) % n], b = line.p[(i + 1) % n] - line.p[i];
    const double na = a.norm(), nb = b.norm();
    if (!(na > 0 && nb > 0)) continue;
    const double angle = std::acos(std::clamp(a.dot(b) / (na * nb), -1.0, 1.0));
    if (angle > c.angle) c = Corner{angle, i};
  }
  return c;
}

// The point of a row farthest from the centre of the row's bounding box: a function of the
// row's points, not of their order. Distances within kTie of the farthest are equal (a
// symmetric section); of those, the one nearest to a point of `next` (the next row: a regular
// polygon's points are all equally far, and the one its neighbour's points line up with wins),
// then the row's first point if it is still one of them, so rows that already start there are
// kept, else the lexicographically smallest.
std::size_t farthest(std::span<const Point> p, std::span<const Point> next) {
  Point lo = p[0], hi = p[0];
  for (const Point& q : p) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const Point centre = 0.5 * (lo + hi);
  double far = 0;
  for (const Point& q : p) far = std::max(far, (q - centre).norm());
  std::vector<std::size_t> tied;
  for (std::size_t i = 0; i < p.size(); ++i)
    if ((p[i] - centre).norm() >= far * (1 - kTie)) tied.push_back(i);
  if (tied.size() > 1 && !next.empty() && tied.size() * next.size() <= kTieWork) {
    std::vector<double> near(tied.size(), std::numeric_limits<double>::infinity());
    double nearest = near[0];
    for (std::size_t t = 0; t < tied.size(); ++t) {
      for (const Point& q : next) near[t] = std::min(near[t], (q - p[tied[t]]).norm());
      nearest = std::min(nearest, near[t]);
    }
    std::vector<std::size_t> closest;
    for (std::size_t t = 0; t < tied.size(); ++t)
      if (near[t] <= nearest + kTie * far) closest.push_back(tied[t]);
    tied = std::move(closest);
  }
  if (tied.front() == 0) return 0;
  std::size_t best = tied.front();
  for (std::size_t i : tied)
    if (std::tie(p[i].x(), p[i].y(), p[i].z()) < std::tie(p[best].x(), p[best].y(), p[best].z()))
      best = i;
  return best;
}

namespace {

// The seam at position s (wrapped) of a closed row: the nearest point and the offset past it.
RowSeam seam_at(const Polyline& line, double s, bool reversed) {
  const std::size_t n = line.p.size();
  s -= std::floor(s);
  std::size_t i = 0;
  double best = 2;
  for (std::size_t k = 0; k < n; ++k) {
    double d = std::fabs(line.at[k] - s);
    d = std::min(d, 1 - d);
    if (d < best) best = d, i = k;
  }
  double ahead = reversed ? line.at[i] - s : s - line.at[i];
  ahead -= std::floor(ahead + 0.5);
  const double next = (i + 1 < n ? line.at[i + 1] : 1.0) - line.at[i];
  const double prev = line.at[i] - (i > 0 ? line.at[i - 1] : line.at[n - 1] - 1.0);
  const double spacing = (ahead >= 0) == !reversed ? next : prev;
  return RowSeam{static_cast<long>(i), reversed, spacing > 0 ? ahead / spacing : 0.0};
}

}  // namespace

}  // namespace sfit::detail::row_match
