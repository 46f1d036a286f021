// Whether a surface stays between its rows (between_rows.h).
#include "between_rows.h"

#include <algorithm>
#include <cmath>

namespace sfit::detail {

namespace {

constexpr std::size_t kPairsPerRow = 16;

}  // namespace

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
      std::size_t near = 0;
      double best = (b[0] - a[i]).squaredNorm();
      for (std::size_t l = 1; l < b.size(); ++l)
        if (const double d2 = (b[l] - a[i]).squaredNorm(); d2 < best) best = d2, near = l;
      out.points.push_back({rows.offsets()[j] + i, rows.offsets()[next] + near});
      out.gap.push_back(std::sqrt(best));
    }
  }
  return out;
}

double between_rows_ratio(const Surface& s, const Rows& rows, const RowPairs& pairs,
                          std::span<const double> u, std::span<const double> v, double t) {
  const bool per_point = v.size() == rows.total_points();
  std::vector<std::size_t> row_of;
  if (!per_point) {
    row_of.resize(rows.total_points());
    for (std::size_t j = 0; j < rows.size(); ++j)
      std::fill(row_of.begin() + static_cast<std::ptrdiff_t>(rows.offsets()[j]),
                row_of.begin() + static_cast<std::ptrdiff_t>(rows.offsets()[j + 1]), j);
  }
  const std::span<const Point> points = rows.points();
  const double ue = s.u_end(), ve = s.v_end();
  double worst = 0;
  for (std::size_t k = 0; k < pairs.points.size(); ++k) {
    const auto [a, b] = pairs.points[k];
    double ua = u[a], ub = u[b];
    if (s.periodic_u && std::abs(ua - ub) > 0.5 * ue) (ua < ub ? ua : ub) += ue;
    double va = per_point ? v[a] : v[row_of[a]], vb = per_point ? v[b] : v[row_of[b]];
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
