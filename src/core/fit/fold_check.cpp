#include "sfit/fold_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "basis_knots.h"

namespace sfit {
namespace {

constexpr int kPerStretch = 16;  // samples between two rows
constexpr int kGapSamples = 32;  // samples along u for the gap between rows

int spans(int count, int degree, bool periodic) {
  return periodic ? count : count - degree;
}

// Control points of the column curve v -> S(u, v) at u (count_v of them), and of its
// derivative in u, v -> S_u(u, v).
void column_at(const Surface& s, double u, std::vector<Point>& col, std::vector<Point>& col_u) {
  std::array<double, 2 * (kMaxDegree + 1)> bu;
  const int w = s.degree_u + 1;
  const int fu = basis_derivatives_u(s, u, 1, bu.data());
  col.assign(static_cast<std::size_t>(s.count_v), Point::Zero());
  col_u.assign(static_cast<std::size_t>(s.count_v), Point::Zero());
  for (int a = 0; a <= s.degree_u; ++a) {
    const int i = wrap_index(fu + a, s.count_u);
    for (int l = 0; l < s.count_v; ++l) {
      col[l] += bu[a] * s.at(i, l);
      col_u[l] += bu[w + a] * s.at(i, l);
    }
  }
}

// The basis across at one v: its first index and values.
struct BasisAt {
  int first = 0;
  std::array<double, kMaxDegree + 1> values;
};

BasisAt basis_at_v(const Surface& s, double v) {
  BasisAt b;
  b.first = basis_v(s, v, b.values.data());
  return b;
}

// S(u, v) on the column `col` at u, with the basis across at v made once (basis_at_v()): the
// samples of every column share their v, so their bases are evaluated once per fit, not once
// per column (the same values, summed in the same order).
Point column_point(const Surface& s, const std::vector<Point>& col, const BasisAt& bv) {
  Point p = Point::Zero();
  for (int b = 0; b <= s.degree_v; ++b)
    p += bv.values[b] * col[wrap_index(bv.first + b, s.count_v)];
  return p;
}

// S, S_u and S_v at v on the column.
struct Sample {
  Point p, normal;
};
Sample column_sample(const Surface& s, const std::vector<Point>& col,
                     const std::vector<Point>& col_u, double v) {
  std::array<double, 2 * (kMaxDegree + 1)> bv;
  const int w = s.degree_v + 1;
  const int fv = basis_derivatives_v(s, v, 1, bv.data());
  Point p = Point::Zero(), su = Point::Zero(), sv = Point::Zero();
  for (int b = 0; b <= s.degree_v; ++b) {
    const int l = wrap_index(fv + b, s.count_v);
    p += bv[b] * col[l];
    su += bv[b] * col_u[l];
    sv += bv[w + b] * col[l];
  }
  return {p, su.cross(sv)};
}

// The stretches [v_j, v_{j+1}] between consecutive rows (closed: also the last to the first).
std::vector<std::pair<double, double>> stretches(const Surface& s, std::span<const double> v) {
  std::vector<std::pair<double, double>> out;
  for (std::size_t j = 0; j + 1 < v.size(); ++j)
    if (v[j + 1] > v[j]) out.emplace_back(v[j], v[j + 1]);
  if (s.periodic_v && v.size() > 1) out.emplace_back(v.back(), v.front() + s.v_end());
  return out;
}

// 8 per knot span along u, at least 64, within a budget of samples (a 10^6-point fit must not
// spend more on its measures than on the fit: 2e5 samples cost about 20 ms).
constexpr double kSampleBudget = 1e5;
int u_samples(const Surface& s, std::size_t stretches, double budget) {
  const int want = std::max(64, 8 * spans(s.count_u, s.degree_u, s.periodic_u));
  const double per_column = std::max<double>(1, static_cast<double>(stretches)) * (kPerStretch + 1);
  return std::clamp(static_cast<int>(budget / per_column), 16, want);
}

template <class Visit>
double fold_and_visit(const Surface& s, std::span<const double> v, double budget, Visit&& visit) {
  const auto st = stretches(s, v);
  const int nu = u_samples(s, st.size(), budget);
  // The bases across at every stretch's samples, the same for every column.
  std::vector<BasisAt> across;
  across.reserve(st.size() * (kPerStretch + 1));
  for (const auto& [v0, v1] : st)
    for (int k = 0; k <= kPerStretch; ++k)
      across.push_back(basis_at_v(s, v0 + (v1 - v0) * k / kPerStretch));
  std::vector<Point> col, col_u;
  std::array<Point, kPerStretch + 1> p;
  double fold = 0;
  for (int a = 0; a <= nu; ++a) {
    if (s.periodic_u && a == nu) break;
    column_at(s, s.u_end() * a / nu, col, col_u);
    const BasisAt* bv = across.data();
    for (const auto& [v0, v1] : st) {
      for (int k = 0; k <= kPerStretch; ++k, ++bv) {
        p[k] = column_point(s, col, *bv);
        visit(p[k]);
      }
      const Point chord = p[kPerStretch] - p[0];
      const double len = chord.norm();
      if (!(len > 0)) continue;
      const Point dir = chord / len;
      double reach = 0, back = 0;
      for (int k = 1; k <= kPerStretch; ++k) {
        const double x = (p[k] - p[0]).dot(dir);
        back = std::max(back, reach - x);
        reach = std::max(reach, x);
      }
      if (!(back > fold)) continue;
      // A column that turns (a lip, a U-turn of the data) keeps its normal turning smoothly;
      // one that doubles back on itself reverses it. (Normals only where it runs back.)
      bool reverses = false;
      Point prev = Point::Zero();
      for (int k = 0; k <= kPerStretch && !reverses; ++k) {
        const Point n = column_sample(s, col, col_u, v0 + (v1 - v0) * k / kPerStretch).normal;
        reverses = k > 0 && n.dot(prev) < 0;
        prev = n;
      }
      if (reverses) fold = back;
    }
  }
  return fold;
}

// Distance from q to the polyline of `row`, over the segments within `window` points of
// point `near` (all of them when the window covers the row).
double distance_to_polyline(const Point& q, std::span<const Point> row, bool closed,
                            std::size_t near, std::size_t window) {
  const std::size_t n = row.size();
  double best = (q - row[near]).squaredNorm();
  if (n < 2) return std::sqrt(best);
  const std::size_t segments = closed ? n : n - 1;
  const bool all = 2 * window + 1 >= segments;
  const long lo = all ? 0 : static_cast<long>(near) - static_cast<long>(window);
  const long hi = all ? static_cast<long>(segments) - 1 : static_cast<long>(near + window);
  for (long m = lo; m <= hi; ++m) {
    long i = m;
    if (closed) {
      i %= static_cast<long>(n);
      if (i < 0) i += static_cast<long>(n);
    } else if (i < 0 || i >= static_cast<long>(segments)) {
      continue;
    }
    const Point& a = row[static_cast<std::size_t>(i)];
    const Point ab = row[(static_cast<std::size_t>(i) + 1) % n] - a;
    const double l2 = ab.squaredNorm();
    const double t = l2 > 0 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * ab - q).squaredNorm());
  }
  return std::sqrt(best);
}

// The point of a row whose parameter is nearest t. The parameters run up along the row,
// cyclically for a closed one (from the point `first` with the smallest one): binary search.
std::size_t nearest_parameter(std::span<const double> u, std::size_t first, double t) {
  const std::size_t n = u.size();
  auto at = [&](std::size_t k) { return u[(first + k) % n]; };
  std::size_t lo = 0, hi = n;  // first k with at(k) >= t
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (at(mid) < t) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  if (lo == n) return (first + n - 1) % n;
  if (lo > 0 && t - at(lo - 1) < at(lo) - t) --lo;
  return (first + lo) % n;
}

}  // namespace

double fold_measure(const Surface& s, std::span<const double> v) {
  return fold_and_visit(s, v, kSampleBudget, [](const Point&) {});
}

ShapeMeasures measure_shape(const Surface& s, const Rows& rows, std::span<const double> u,
                            std::span<const double> v, const BoundingBox& box, bool closed_u) {
  ShapeMeasures m;
  // In a fit: samples within a quarter of the data's points (at least 2e4, at most 1e5), so
  // the measures stay a small part of the fit.
  const double budget =
      std::clamp(0.25 * static_cast<double>(rows.total_points()), 2e4, kSampleBudget);
  m.fold = fold_and_visit(s, v, budget, [&](const Point& p) {
    const Point out = (box.min - p).cwiseMax(p - box.max).cwiseMax(Point::Zero());
    m.box_excursion = std::max(m.box_excursion, out.norm());
  });
  // 32 samples per stretch; each searches the two rows' polylines within 1/32 of the row
  // (at least 8 points) around the point whose parameter is nearest.
  for (std::size_t j = 0; j + 1 < rows.size() && j + 1 < v.size(); ++j) {
    const double mid = 0.5 * (v[j] + v[j + 1]);
    std::size_t first[2] = {0, 0};
    for (std::size_t r : {j, j + 1}) {
      const double* ur = u.data() + rows.offsets()[r];
      first[r - j] = static_cast<std::size_t>(std::min_element(ur, ur + rows[r].size()) - ur);
    }
    for (int a = 0; a < kGapSamples; ++a) {
      const double t = s.u_end() * (a + 0.5) / kGapSamples;
      const Point q = s.evaluate(t, mid);
      double d = std::numeric_limits<double>::infinity();
      for (std::size_t r : {j, j + 1}) {
        const auto row = rows[r];
        const std::span<const double> ur(u.data() + rows.offsets()[r], row.size());
        const std::size_t near = nearest_parameter(ur, first[r - j], t);
        d = std::min(d, distance_to_polyline(q, row, closed_u, near,
                                             std::max<std::size_t>(8, row.size() / 32)));
      }
      m.row_gap = std::max(m.row_gap, d);
    }
  }
  return m;
}

}  // namespace sfit
