#include "sfit/seam_alignment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "sfit/parametrization.h"

namespace sfit {
namespace {

constexpr int kSamples = 64;          // equal arc-length samples compared per row
constexpr double kKeepSlack = 1.02;   // the given direction wins unless 2 % worse than the other
constexpr double kKeepOffset = 1e-3;  // the given start wins within this fraction of a spacing
constexpr double kFlipRatio = 0.5;    // an open row is reversed when that halves the cost
constexpr double kTie = 1e-9;         // distances this close (relative) are equal
constexpr std::size_t kTieWork = 1 << 22;  // distances compared to break ties, at most
constexpr double kRoundoffOffset = 1e-9;   // seam offsets below this are rounding: 0
constexpr int kGoldenSteps = 56;           // a bracket of 2 spacings to 4e-12 of one
constexpr double kCornerAngle = 1.5;       // radians: a turn this sharp is a corner (an edge)

// A row as a polyline parametrised by the positions the fit gives its points (index
// fractions for the paper's rule, chord-length fractions for chord, ...): closed rows wrap.
struct Polyline {
  std::span<const Point> p;
  bool closed = false;
  std::vector<double> at;  // position of each point; at[n] = 1 when closed
  double total = 1;

  Polyline(std::span<const Point> pts, bool c, Parametrization rule) : p(pts), closed(c) {
    const std::size_t n = p.size();
    at = normalized_positions(p, rule, closed);
    at.push_back(1.0);
    double length = 0;
    for (std::size_t i = 1; i < n; ++i) length += (p[i] - p[i - 1]).norm();
    if (!(length > 0) || !std::isfinite(length)) total = 0;
  }
  // The point at arc length s (wrapped when closed, clamped when open).
  Point operator()(double s) const {
    const std::size_t n = p.size();
    if (closed) {
      s = std::fmod(s, total);
      if (s < 0) s += total;
    } else {
      s = std::clamp(s, 0.0, total);
    }
    const std::size_t segments = closed ? n : n - 1;
    // Segment i runs from at[i] to at[i + 1].
    std::size_t i = static_cast<std::size_t>(
        std::upper_bound(at.begin(), at.begin() + static_cast<std::ptrdiff_t>(segments + 1), s) -
        at.begin());
    i = i == 0 ? 0 : std::min(i - 1, segments - 1);
    const double len = at[i + 1] - at[i];
    if (!(len > 0)) return p[i];
    const double w = std::clamp((s - at[i]) / len, 0.0, 1.0);
    // Cubic Hermite with finite-difference (Catmull-Rom) tangents: rows sampled from smooth
    // sections of different point counts then match at fractions of a spacing far better
    // than their polylines (whose chords sag differently).
    // k runs over a - 1 ... b + 1, within -1 ... n + 1 (n >= 2): at most one wrap either way,
    // taken without an integer division (this runs 64 times per sample set, thousands of sets
    // per fit of closed rows).
    const long nn = static_cast<long>(n);
    auto wraps_of = [&](long k) -> long { return k < 0 ? -1 : (k >= nn ? 1 : 0); };
    auto point = [&](long k) { return p[static_cast<std::size_t>(k - wraps_of(k) * nn)]; };
    auto pos = [&](long k) {
      const long wraps = wraps_of(k);
      return at[static_cast<std::size_t>(k - wraps * nn)] + static_cast<double>(wraps);
    };
    const long a = static_cast<long>(i), b = a + 1;
    auto tangent = [&](long k) -> Point {
      long lo = k - 1, hi = k + 1;
      if (!closed) lo = std::max(lo, 0L), hi = std::min(hi, static_cast<long>(n) - 1);
      const double dt = pos(hi) - pos(lo);
      return dt > 0 ? Point((point(hi) - point(lo)) / dt) : Point::Zero();
    };
    const double w2 = w * w, w3 = w2 * w;
    return (2 * w3 - 3 * w2 + 1) * point(a) + (w3 - 2 * w2 + w) * len * tangent(a) +
           (-2 * w3 + 3 * w2) * point(b) + (w3 - w2) * len * tangent(b);
  }
};

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

// The start and direction of closed row `line` that best match reference samples `ref`.
struct Choice {
  RowSeam seam;
  double start = 0;  // position of the aligned row's start on the original polyline
};

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

struct Corner {
  double angle = 0;  // turning angle in radians
  std::size_t index = 0;
};

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

std::string_view to_string(SeamMode m) {
  return m == SeamMode::kKeep ? "keep" : "align";
}
std::string_view to_string(OrientMode m) {
  return m == OrientMode::kKeep ? "keep" : "auto";
}
bool parse_seam_mode(std::string_view name, SeamMode& out) {
  if (name == "align")
    out = SeamMode::kAlign;
  else if (name == "keep")
    out = SeamMode::kKeep;
  else
    return false;
  return true;
}
bool parse_orient_mode(std::string_view name, OrientMode& out) {
  if (name == "auto")
    out = OrientMode::kAuto;
  else if (name == "keep")
    out = OrientMode::kKeep;
  else
    return false;
  return true;
}

RowAlignment align_rows(const Rows& rows, bool closed_u, SeamMode seam, OrientMode orient,
                        Parametrization rule) {
  if (rule != Parametrization::kChord && rule != Parametrization::kCentripetal)
    rule = Parametrization::kUniform;
  RowAlignment a;
  a.rows.assign(rows.size(), RowSeam{});
  const bool shifts = closed_u && seam == SeamMode::kAlign;
  const bool directions = orient == OrientMode::kAuto;
  if (!shifts && !directions) return a;
  std::vector<Point> ref;  // samples of the last usable row as aligned
  Corner corner;
  std::size_t corner_row = 0;
  std::size_t first = rows.size();  // the first usable row
  std::vector<char> aligned(rows.size(), 0);
  std::size_t ref_points = 0;  // points of the reference row, and its seam's offset
  double ref_offset = 0;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const auto row = rows[j];
    if (!usable(row)) continue;
    const Polyline line(row, closed_u, rule);
    if (!(line.total > 0) || !std::isfinite(line.total)) continue;
    Choice c;
    if (!ref.empty()) {
      if (closed_u) {
        c = align_closed(line, ref, shifts, directions,
                         row.size() == ref_points ? &ref_offset : nullptr);
      } else {
        const double forwards = cost(samples(line, 0, false), ref);
        const double backwards = cost(samples(line, 0, true), ref);
        if (backwards < kFlipRatio * forwards)
          c.seam = RowSeam{static_cast<long>(row.size()) - 1, true};
      }
    }
    a.rows[j] = c.seam;
    aligned[j] = 1;
    if (first == rows.size()) first = j;
    ref = samples(line, c.start, c.seam.reversed);
    ref_points = row.size();
    ref_offset = c.seam.offset;
    if (shifts) {
      const Corner k = sharpest(line);
      if (k.angle > corner.angle) {
        corner = k;
        corner_row = j;
      }
    }
  }
  // Every seam moves by the same fraction of its row's points onto a point that depends on the
  // rows' points only, not on where or which way round they are given, so rotated and reversed
  // copies of the rows fit the same surface: the sharpest corner of any row (a trailing edge),
  // so the knots meet it the same way, or else the point of the first row farthest from its
  // box's centre. Fractions of the points (not of the rule's positions), so every rule moves
  // the seams alike.
  if (shifts && first < rows.size()) {
    std::size_t after = first + 1;  // the next usable row
    while (after < rows.size() && !aligned[after]) ++after;
    std::size_t j = first,
                index = farthest(rows[first],
                                 after < rows.size() ? rows[after] : std::span<const Point>());
    if (corner.angle > kCornerAngle) j = corner_row, index = corner.index;
    // Seams as index positions: point shift + offset, forwards along the original points.
    auto at_index = [](const RowSeam& seam) {
      return static_cast<double>(seam.shift) + (seam.reversed ? -seam.offset : seam.offset);
    };
    const RowSeam& ref_seam = a.rows[j];
    const double nj = static_cast<double>(rows[j].size());
    double phi = (ref_seam.reversed ? at_index(ref_seam) - static_cast<double>(index)
                                    : static_cast<double>(index) - at_index(ref_seam)) /
                 nj;
    phi -= std::floor(phi + 0.5);  // (-1/2, 1/2]
    if (phi != 0)
      for (std::size_t r = 0; r < rows.size(); ++r) {
        if (!aligned[r]) continue;
        RowSeam& seam = a.rows[r];
        const double n = static_cast<double>(rows[r].size());
        const double x = at_index(seam) + (seam.reversed ? -phi : phi) * n;
        const double whole = std::floor(x + 0.5);
        double offset = seam.reversed ? whole - x : x - whole;
        if (std::fabs(offset) < kRoundoffOffset) offset = 0;
        const long nn = static_cast<long>(rows[r].size());
        seam = RowSeam{((static_cast<long>(whole) % nn) + nn) % nn, seam.reversed, offset};
      }
  }
  return a;
}

Rows apply_alignment(const Rows& rows, const RowAlignment& a) {
  Rows out;
  out.reserve(rows.total_points(), rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const auto row = rows[j];
    const auto w = rows.row_weights(j);
    for (std::size_t k = 0; k < row.size(); ++k) {
      const std::size_t i = source_index(a.rows[j], row.size(), k);
      out.push_point(row[i]);
      if (!w.empty()) out.push_weight(w[i]);
    }
    out.end_row();
  }
  return out;
}

std::vector<std::size_t> original_indices(const Rows& rows, const RowAlignment& a) {
  std::vector<std::size_t> idx(rows.total_points());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const std::size_t n = rows[j].size(), o = rows.offsets()[j];
    for (std::size_t k = 0; k < n; ++k) idx[o + k] = o + source_index(a.rows[j], n, k);
  }
  return idx;
}

}  // namespace sfit
