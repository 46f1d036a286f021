// Matching one row of points to its neighbour (seam_alignment.h's align_rows()): a row as a
// polyline at the rule's positions, equal-arc-length samples of it and their distance, the
// start and direction of a closed row that best match its neighbour's samples, and the points
// a seam moves onto (a row's sharpest corner, its point farthest from its box's centre).
// Private to seam_alignment.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "sfit/parametrization.h"
#include "sfit/seam_alignment.h"

namespace sfit::detail::row_match {

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

/// At least 3 points, not all equal.
bool usable(std::span<const Point> row);
/// Samples of `line` at equal fractions starting at arc length `start`, going forwards or
/// backwards (closed), or over the whole open row; centred on their mean.
std::vector<Point> samples(const Polyline& line, double start, bool backwards);
/// The squared distance of two sample sets.
double cost(const std::vector<Point>& a, const std::vector<Point>& b);

/// The start and direction of closed row `line` that best match reference samples `ref`.
struct Choice {
  RowSeam seam;
  double start = 0;  // position of the aligned row's start on the original polyline
};
/// `follow`: the row has as many points as the reference row, whose seam lies *follow point
/// spacings past its first point; this row's seam then lies as far past one of its points.
Choice align_closed(const Polyline& line, const std::vector<Point>& ref, bool shifts,
                    bool directions, const double* follow);

struct Corner {
  double angle = 0;  // turning angle in radians
  std::size_t index = 0;
};
/// The row's sharpest turn (closed: around the wrap too).
Corner sharpest(const Polyline& line);

/// The point of a row farthest from the centre of the row's bounding box (ties: see the
/// definition), `next` the next row.
std::size_t farthest(std::span<const Point> p, std::span<const Point> next);

}  // namespace sfit::detail::row_match
