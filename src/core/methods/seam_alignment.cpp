#include "sfit/seam_alignment.h"

#include <cmath>

#include "row_matching.h"

namespace sfit {

using namespace detail::row_match;

namespace {

constexpr double kFlipRatio = 0.5;        // an open row is reversed when that halves the cost
constexpr double kRoundoffOffset = 1e-9;  // seam offsets below this are rounding: 0
constexpr double kCornerAngle = 1.5;      // radians: a turn this sharp is a corner (an edge)

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
