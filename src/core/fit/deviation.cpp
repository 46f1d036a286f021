#include "deviation.h"

#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "basis_knots.h"
#include "parallel.h"

namespace sfit {

namespace {

// The check of rows [j0, j1).
DeviationCheck check_rows(const Surface& s, const Rows& rows, std::span<const double> u,
                          std::span<const double> v, const Point& tol, double roundoff,
                          std::size_t j0, std::size_t j1) {
  DeviationCheck out;
  std::array<double, kMaxDegree + 1> bv, bu;
  std::vector<Point> iso(static_cast<std::size_t>(s.count_u));
  const auto& off = rows.offsets();
  const bool per_point = v.size() != rows.size();
  RowBasis row_basis(s);  // kept across rows with the same u
  for (std::size_t j = j0; j < j1; ++j) {
    // The iso-curve v = v_j: its control points Q_i = sum_l B_l(v_j) P_il, once per row.
    const int fv = per_point ? 0 : basis_v(s, v[j], bv.data());
    for (int i = 0; i < s.count_u && !per_point; ++i) {
      Point q = Point::Zero();
      for (int b = 0; b <= s.degree_v; ++b) q += bv[b] * s.at(i, wrap_index(fv + b, s.count_v));
      iso[i] = q;
    }
    const auto row = rows[j];
    const std::span<const double> uj = u.subspan(off[j], row.size());
    if (!per_point) row_basis.of(uj);
    for (std::size_t k = 0; k < row.size(); ++k) {
      Point p = Point::Zero();
      if (per_point) {
        const int fu = basis_u(s, uj[k], bu.data());
        p = point_at(s, bu.data(), fu, v[off[j] + k]);
      } else {
        const double* b = row_basis.values(k);
        const int fu = row_basis.first(k);
        for (int a = 0; a <= s.degree_u; ++a) p += b[a] * iso[wrap_index(fu + a, s.count_u)];
      }
      const Point d = p - row[k];
      const Point ad = d.cwiseAbs();
      if (!ad.allFinite()) {
        out.within = false;
        out.worst_ratio = std::numeric_limits<double>::infinity();
        out.worst_row = static_cast<long>(j);
        out.worst_index = static_cast<long>(k);
        out.worst_deviation = d;
        continue;
      }
      out.max_deviation = out.max_deviation.cwiseMax(ad);
      double ratio = 0;
      for (int a = 0; a < 3; ++a) {
        if (ad[a] > tol[a] + (tol[a] == 0 ? roundoff : 0.0)) out.within = false;
        const double r = tol[a] > 0 ? ad[a] / tol[a] : (ad[a] > roundoff ? ad[a] / roundoff : 0);
        ratio = std::max(ratio, r);
      }
      if (out.worst_row < 0 || ratio > out.worst_ratio) {
        out.worst_ratio = ratio;
        out.worst_row = static_cast<long>(j);
        out.worst_index = static_cast<long>(k);
        out.worst_deviation = d;
      }
    }
  }
  return out;
}

}  // namespace

DeviationCheck check_deviation(const Surface& s, const Rows& rows, std::span<const double> u,
                               std::span<const double> v, const Point& tol, double roundoff,
                               int threads) {
  threads = detail::resolve_threads(threads);
  const std::size_t M = rows.size();
  if (threads <= 1 || rows.total_points() < 20000)
    return check_rows(s, rows, u, v, tol, roundoff, 0, M);
  // Fixed blocks of rows, merged in order as one pass would: the largest ratio first met
  // wins, except that a non-finite deviation, once met, is reported (the last one met).
  constexpr std::size_t kBlocks = 64;
  const std::size_t per = (M + kBlocks - 1) / kBlocks;
  const std::size_t n_blocks = (M + per - 1) / per;
  std::vector<DeviationCheck> part(n_blocks);
  detail::parallel_for(n_blocks, threads, [&](std::size_t b) {
    part[b] = check_rows(s, rows, u, v, tol, roundoff, b * per, std::min(M, (b + 1) * per));
  });
  DeviationCheck out;
  for (const DeviationCheck& r : part) {
    out.within = out.within && r.within;
    out.max_deviation = out.max_deviation.cwiseMax(r.max_deviation);
    if (r.worst_row < 0) continue;
    const bool not_finite = !r.worst_deviation.allFinite();
    if (out.worst_row < 0 || not_finite || r.worst_ratio > out.worst_ratio) {
      out.worst_ratio = r.worst_ratio;
      out.worst_row = r.worst_row;
      out.worst_index = r.worst_index;
      out.worst_deviation = r.worst_deviation;
    }
  }
  return out;
}

}  // namespace sfit
