// The geometric rule's checks on a surface and its parameters (geometric_search.h): which knot
// spans hold data, whether the surface stays near the data's box there and calm elsewhere, its
// fold across, the three checks a surface of the rule holds with (judge_with_guards()), and the
// parameters as fractions of the domain. Shared by the rule's search and the fallback below the
// points.
#include <algorithm>
#include <cmath>

#include "geometric_search.h"
#include "sfit/fold_check.h"

namespace sfit::detail {

namespace {

// Beyond this fraction of the data's diagonal outside its box, a span without data is no
// longer calm (the guard of fit_frame.h allows a tenth where the data is).
constexpr double kCalmMargin = 0.5;

// The cells (u-major, su x sv) that hold data or lie between two that do in their column or
// in their row.
std::vector<char> between_covered(const std::vector<char>& cell, int su, int sv) {
  std::vector<char> out = cell;
  for (int a = 0; a < su; ++a) {
    int first = sv, last = -1;
    for (int b = 0; b < sv; ++b)
      if (cell[static_cast<std::size_t>(a) * sv + b]) first = std::min(first, b), last = b;
    for (int b = first + 1; b < last; ++b) out[static_cast<std::size_t>(a) * sv + b] = 1;
  }
  for (int b = 0; b < sv; ++b) {
    int first = su, last = -1;
    for (int a = 0; a < su; ++a)
      if (cell[static_cast<std::size_t>(a) * sv + b]) first = std::min(first, a), last = a;
    for (int a = first + 1; a < last; ++a) out[static_cast<std::size_t>(a) * sv + b] = 1;
  }
  return out;
}

}  // namespace

std::vector<char> covered_spans(const Surface& s, std::span<const double> u,
                                std::span<const double> v) {
  const int su = s.periodic_u ? s.count_u : s.count_u - s.degree_u;
  const int sv = s.periodic_v ? s.count_v : s.count_v - s.degree_v;
  std::vector<char> cell(static_cast<std::size_t>(su) * sv, 0);
  for (std::size_t k = 0; k < u.size(); ++k) {
    const int a = std::clamp(static_cast<int>(std::floor(u[k])), 0, su - 1);
    const int b = std::clamp(static_cast<int>(std::floor(v[k])), 0, sv - 1);
    cell[static_cast<std::size_t>(a) * sv + b] = 1;
  }
  return cell;
}

bool stays_near_where_covered(const Surface& s, std::span<const double> u,
                              std::span<const double> v, const BoundingBox& box) {
  const double d = box.diagonal();
  auto within = [&](const Point& p, double margin) {
    return (p.array() >= (box.min.array() - margin)).all() &&
           (p.array() <= (box.max.array() + margin)).all();
  };
  bool hull_inside = true;  // then no sample can leave the box grown by a tenth
  for (const Point& p : s.control) {
    if (!within(p, d)) return false;
    hull_inside = hull_inside && within(p, 0.1 * d);
  }
  if (hull_inside) return true;
  std::vector<char> cell = covered_spans(s, u, v);
  const int su = s.periodic_u ? s.count_u : s.count_u - s.degree_u;
  const int sv = s.periodic_v ? s.count_v : s.count_v - s.degree_v;
  // A span between spans with data, along u or along v, lies between the data, not outside
  // its outline: it is held as near as they are. (Ship stations 2.6 m apart, each in one span
  // of 190 along v, once took 4 x 193 control points whose columns swung 11 m, 0.16 of the
  // diagonal, out of the box between every two stations.)
  cell = between_covered(cell, su, sv);
  for (int a = 0; a <= 4 * su; ++a)
    for (int b = 0; b <= 4 * sv; ++b) {
      // A sample on a span's edge belongs to every span it touches.
      bool data = false;
      for (int x : {(a - 1) / 4, a / 4})
        for (int y : {(b - 1) / 4, b / 4})
          if (x >= 0 && y >= 0 && x < su && y < sv && cell[static_cast<std::size_t>(x) * sv + y])
            data = true;
      const Point p = s.evaluate(s.u_end() * a / (4 * su), s.v_end() * b / (4 * sv));
      if (!within(p, data ? 0.1 * d : kCalmMargin * d)) return false;
    }
  return true;
}

void to_fractions(const Surface& s, const std::vector<double>& u, const std::vector<double>& v,
                  std::vector<double>& fu, std::vector<double>& fv) {
  fu.resize(u.size());
  fv.resize(v.size());
  const double ue = s.u_end(), ve = s.v_end();
  for (std::size_t k = 0; k < u.size(); ++k) {
    fu[k] = u[k] / ue;
    if (s.periodic_u && fu[k] >= 1) fu[k] = 0;
    fv[k] = v[k] / ve;
  }
}

double geometric_fold(const Surface& s) {
  const int n = 2 * s.count_v + 1;
  std::vector<double> grid(static_cast<std::size_t>(n));
  const double e = s.v_end();
  for (int k = 0; k < n; ++k) grid[k] = s.periodic_v ? e * k / n : e * k / (n - 1);
  return fold_measure(s, grid);
}

GuardedVerdict judge_with_guards(const Frame& fr, const Surface& s, std::span<const double> u,
                                 std::span<const double> v, DeviationCheck* out,
                                 const Rows* sample) {
  GuardedVerdict g{fr.judge(s, u, v, out, sample, false)};
  if (g.verdict.holds && !stays_near_where_covered(s, u, v, fr.centred_box))
    g.verdict.holds = false;
  if (g.verdict.holds && geometric_fold(s) > kFoldRelative * fr.box.diagonal()) {
    g.verdict.holds = false;
    g.folded = true;
  }
  // Between the rows (on every point's parameters only: a sample's are not the rows').
  if (g.verdict.holds && !sample &&
      between_rows_ratio(s, fr.centred, fr.row_pairs(), u, v, fr.tolerance.maxCoeff()) >
          kBetweenRowsLimit)
    g.verdict.holds = false;
  return g;
}

}  // namespace sfit::detail
