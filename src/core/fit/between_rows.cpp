// Whether a surface stays between its rows (between_rows.h).
#include "between_rows.h"

#include <algorithm>
#include <cmath>

namespace sfit::detail {

namespace {

constexpr std::size_t kPairsPerRow = 16;

}  // namespace

std::size_t nearest_in_row(std::span<const Point> row, const Point& q, double* squared) {
  std::size_t near = 0;
  double best = (row[0] - q).squaredNorm();
  for (std::size_t l = 1; l < row.size(); ++l)
    if (const double d2 = (row[l] - q).squaredNorm(); d2 < best) best = d2, near = l;
  if (squared) *squared = best;
  return near;
}

RowPairs row_pairs(const Rows& rows, bool closed_v) {
  RowPairs out;
  const std::size_t m = rows.size();
  const std::size_t last = closed_v ? m : (m == 0 ? 0 : m - 1);
  for (std::size_t j = 0; j < last; ++j) {
    const std::size_t next = (j + 1) % m;
    if (next == j) continue;
    const auto a = rows[j], b = rows[next];
    if (a.empty() || b.empty()) continue;
    const std::size_t picks = std::min(kPairsPerRow, a.size());
    for (std::size_t k = 0; k < picks; ++k) {
      const std::size_t i = picks == 1 ? 0 : k * (a.size() - 1) / (picks - 1);
      double d2 = 0;
      const std::size_t near = nearest_in_row(b, a[i], &d2);
      out.points.push_back({rows.offsets()[j] + i, rows.offsets()[next] + near});
      out.rows.push_back({j, next});
      out.gap.push_back(std::sqrt(d2));
    }
  }
  return out;
}

double between_rows_ratio(const Surface& s, const Rows& rows, const RowPairs& pairs,
                          std::span<const double> u, std::span<const double> v, double t) {
  const bool per_point = v.size() == rows.total_points();
  const std::span<const Point> points = rows.points();
  const double ue = s.u_end(), ve = s.v_end();
  double worst = 0;
  for (std::size_t k = 0; k < pairs.points.size(); ++k) {
    const auto [a, b] = pairs.points[k];
    const auto [ra, rb] = pairs.rows[k];
    double ua = u[a], ub = u[b];
    if (s.periodic_u && std::abs(ua - ub) > 0.5 * ue) (ua < ub ? ua : ub) += ue;
    double va = v[per_point ? a : ra], vb = v[per_point ? b : rb];
    if (s.periodic_v && std::abs(va - vb) > 0.5 * ve) (va < vb ? va : vb) += ve;
    double um = 0.5 * (ua + ub), vm = 0.5 * (va + vb);
    if (s.periodic_u && um >= ue) um -= ue;
    if (s.periodic_v && vm >= ve) vm -= ve;
    const Point mid = 0.5 * (points[a] + points[b]);
    const double d = (s.evaluate(um, vm) - mid).norm();
    worst = std::max(worst, d / (pairs.gap[k] + 2 * t));
  }
  return worst;
}

}  // namespace sfit::detail
