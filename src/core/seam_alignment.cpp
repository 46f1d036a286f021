#include "sfit/seam_alignment.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "aligned_fit.h"
#include "sfit/parametrization.h"

namespace sfit {
namespace {

constexpr int kSamples = 64;          // equal arc-length samples compared per row
constexpr double kKeepSlack = 1.02;   // the given order wins unless 2 % worse than the best
constexpr double kFlipRatio = 0.5;    // an open row is reversed when that halves the cost
constexpr double kCornerAngle = 1.5;  // radians: a turn this sharp is a corner (an edge)

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
    const double w = len > 0 ? std::clamp((s - at[i]) / len, 0.0, 1.0) : 0.0;
    return (1 - w) * p[i] + w * p[(i + 1) % n];
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

Choice align_closed(const Polyline& line, const std::vector<Point>& ref, bool shifts,
                    bool directions) {
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
  // Fine: every original point within 1.5 coarse steps of the coarse start, that direction.
  const double centre = line.total * coarse_shift / kSamples;
  const double reach = 1.5 * line.total / kSamples;
  RowSeam best;
  double best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    double d = std::fabs(line.at[i] - centre);
    d = std::min(d, line.total - d);
    if (shifts ? d > reach : i != 0) continue;
    const double c = cost(samples(line, line.at[i], coarse_back), ref);
    if (c < best_cost) {
      best_cost = c;
      best = RowSeam{static_cast<long>(i), coarse_back};
    }
  }
  if (!(keep > kKeepSlack * best_cost)) return Choice{};
  const std::size_t i = static_cast<std::size_t>(best.shift);
  Choice out{best, line.at[i]};
  if (!shifts) return out;
  // A fractional start between the neighbouring points (golden section on the cost), given as
  // the fraction of a point spacing the aligned row's start lies past its first point.
  const double before =
      line.at[i] - (i == 0 ? line.at[n] - line.at[n - 1] : line.at[i] - line.at[i - 1]);
  const double after = line.at[i + 1];
  auto at = [&](double s) { return cost(samples(line, s, best.reversed), ref); };
  double a = before, b = after;
  constexpr double g = 0.6180339887498949;
  double x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = at(x1), f2 = at(x2);
  for (int it = 0; it < 24; ++it) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = at(x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = at(x2);
    }
  }
  const double s = f1 < f2 ? x1 : x2;
  if (!(std::min(f1, f2) < best_cost)) return out;
  out.start = s;
  // Past the first point in the aligned row's direction, in that point spacing.
  const double ahead = best.reversed ? line.at[i] - s : s - line.at[i];
  const double spacing = (ahead >= 0) == !best.reversed ? after - line.at[i] : line.at[i] - before;
  out.seam.offset = spacing > 0 ? ahead / spacing : 0.0;
  return out;
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
  std::vector<double> starts(rows.size(), 0.0);
  Corner corner;
  std::size_t corner_row = 0;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const auto row = rows[j];
    if (!usable(row)) continue;
    const Polyline line(row, closed_u, rule);
    if (!(line.total > 0) || !std::isfinite(line.total)) continue;
    Choice c;
    if (!ref.empty()) {
      if (closed_u) {
        c = align_closed(line, ref, shifts, directions);
      } else {
        const double forwards = cost(samples(line, 0, false), ref);
        const double backwards = cost(samples(line, 0, true), ref);
        if (backwards < kFlipRatio * forwards)
          c.seam = RowSeam{static_cast<long>(row.size()) - 1, true};
      }
    }
    a.rows[j] = c.seam;
    ref = samples(line, c.start, c.seam.reversed);
    if (shifts) {
      starts[j] = c.start;
      const Corner k = sharpest(line);
      if (k.angle > corner.angle) {
        corner = k;
        corner_row = j;
      }
    }
  }
  // A sharp corner (a trailing edge) anywhere: every seam moves by the same fraction onto it,
  // so the knots meet the corner the same way whichever point the first row starts at.
  if (shifts && corner.angle > kCornerAngle) {
    const std::size_t j = corner_row;
    const Polyline line(rows[j], true, rule);
    double phi =
        a.rows[j].reversed ? starts[j] - line.at[corner.index] : line.at[corner.index] - starts[j];
    phi -= std::floor(phi + 0.5);  // (-1/2, 1/2]
    if (phi != 0)
      for (std::size_t r = 0; r < rows.size(); ++r) {
        if (!usable(rows[r])) continue;
        const Polyline l(rows[r], true, rule);
        if (!(l.total > 0) || !std::isfinite(l.total)) continue;
        a.rows[r] = seam_at(l, starts[r] + (a.rows[r].reversed ? -phi : phi), a.rows[r].reversed);
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

// The fit's hook (aligned_fit.h).

namespace sfit::detail {

RowAlignment alignment_for(const Rows& rows, const FitOptions& o) {
  return align_rows(rows, o.closed_u, o.seam, o.orient, o.parametrization);
}

std::vector<double> seam_offsets(const RowAlignment& a, bool closed_u) {
  std::vector<double> out;
  if (!closed_u) return out;
  for (const RowSeam& s : a.rows)
    if (s.offset != 0) {
      for (const RowSeam& t : a.rows) out.push_back(t.offset);
      break;
    }
  return out;
}

void shift_positions(std::vector<double>& f, double offset) {
  const std::size_t n = f.size();
  if (offset == 0 || n < 2) return;
  const double start = offset > 0 ? offset * f[1] : offset * (1 - f[n - 1]);
  for (double& x : f) {
    x -= start;
    if (x < 0) x += 1;
    if (x >= 1) x -= 1;
  }
}

void restore_original_order(FitResult& fit, const Rows& original, const RowAlignment& a) {
  const std::vector<std::size_t> idx = original_indices(original, a);
  std::vector<double> u(fit.u.size());
  for (std::size_t k = 0; k < idx.size(); ++k) u[idx[k]] = fit.u[k];
  fit.u = std::move(u);
  FitReport& r = fit.report;
  if (r.worst_row >= 0 && r.worst_index >= 0) {
    const std::size_t j = static_cast<std::size_t>(r.worst_row);
    r.worst_index = static_cast<long>(
        source_index(a.rows[j], original[j].size(), static_cast<std::size_t>(r.worst_index)));
  }
  r.seams = a.rows;
}

}  // namespace sfit::detail
