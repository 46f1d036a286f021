#include "sfit/fold_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "sfit/basis.h"

namespace sfit {
namespace {

constexpr int kPerStretch = 16;  // samples between two rows
constexpr int kGapSamples = 64;  // samples along u for the gap between rows

int spans(int count, int degree, bool periodic) {
  return periodic ? count : count - degree;
}

// Control points of the column curve v -> S(u, v) at u (count_v of them), and of its
// derivative in u, v -> S_u(u, v).
void column_at(const Surface& s, double u, std::vector<Point>& col, std::vector<Point>& col_u) {
  std::array<double, 2 * (kMaxDegree + 1)> bu;
  const int w = s.degree_u + 1;
  const int fu = eval_basis_derivatives(s.degree_u, s.count_u, s.periodic_u, u, 1, bu.data());
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

// S, S_u and S_v at v on the column.
struct Sample {
  Point p, normal;
};
Sample column_sample(const Surface& s, const std::vector<Point>& col,
                     const std::vector<Point>& col_u, double v) {
  std::array<double, 2 * (kMaxDegree + 1)> bv;
  const int w = s.degree_v + 1;
  const int fv = eval_basis_derivatives(s.degree_v, s.count_v, s.periodic_v, v, 1, bv.data());
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

int u_samples(const Surface& s) {
  return std::max(64, 8 * spans(s.count_u, s.degree_u, s.periodic_u));
}

template <class Visit>
double fold_and_visit(const Surface& s, std::span<const double> v, Visit&& visit) {
  const auto st = stretches(s, v);
  const int nu = u_samples(s);
  std::vector<Point> col, col_u;
  std::array<Sample, kPerStretch + 1> q;
  double fold = 0;
  for (int a = 0; a <= nu; ++a) {
    if (s.periodic_u && a == nu) break;
    column_at(s, s.u_end() * a / nu, col, col_u);
    for (const auto& [v0, v1] : st) {
      bool reverses = false;
      for (int k = 0; k <= kPerStretch; ++k) {
        q[k] = column_sample(s, col, col_u, v0 + (v1 - v0) * k / kPerStretch);
        visit(q[k].p);
        if (k > 0 && q[k].normal.dot(q[k - 1].normal) < 0) reverses = true;
      }
      // A column that turns (a lip, a U-turn of the data) keeps its normal turning smoothly;
      // one that doubles back on itself reverses it.
      if (!reverses) continue;
      const Point chord = q[kPerStretch].p - q[0].p;
      const double len = chord.norm();
      if (!(len > 0)) continue;
      const Point dir = chord / len;
      double reach = 0;
      for (int k = 1; k <= kPerStretch; ++k) {
        const double x = (q[k].p - q[0].p).dot(dir);
        fold = std::max(fold, reach - x);
        reach = std::max(reach, x);
      }
    }
  }
  return fold;
}

double distance_to_polyline(const Point& q, std::span<const Point> row, bool closed) {
  const std::size_t n = row.size();
  double best = (q - row[0]).squaredNorm();
  const std::size_t segments = closed ? n : n - 1;
  for (std::size_t i = 0; i < segments && n > 1; ++i) {
    const Point& a = row[i];
    const Point ab = row[(i + 1) % n] - a;
    const double l2 = ab.squaredNorm();
    const double t = l2 > 0 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * ab - q).squaredNorm());
  }
  return std::sqrt(best);
}

}  // namespace

double fold_measure(const Surface& s, std::span<const double> v) {
  return fold_and_visit(s, v, [](const Point&) {});
}

ShapeMeasures measure_shape(const Surface& s, const Rows& rows, std::span<const double> v,
                            const BoundingBox& box, bool closed_u) {
  ShapeMeasures m;
  m.fold = fold_and_visit(s, v, [&](const Point& p) {
    const Point out = (box.min - p).cwiseMax(p - box.max).cwiseMax(Point::Zero());
    m.box_excursion = std::max(m.box_excursion, out.norm());
  });
  std::vector<Point> col;
  for (std::size_t j = 0; j + 1 < rows.size() && j + 1 < v.size(); ++j) {
    const double mid = 0.5 * (v[j] + v[j + 1]);
    for (int a = 0; a < kGapSamples; ++a) {
      const double u = s.u_end() * (a + 0.5) / kGapSamples;
      const Point q = s.evaluate(u, mid);
      m.row_gap = std::max(m.row_gap, std::min(distance_to_polyline(q, rows[j], closed_u),
                                               distance_to_polyline(q, rows[j + 1], closed_u)));
    }
  }
  return m;
}

}  // namespace sfit
