#include "sfit/deviation.h"

#include <array>
#include <cmath>
#include <limits>

#include "sfit/basis.h"

namespace sfit {

DeviationCheck check_deviation(const Surface& s, const Rows& rows, std::span<const double> u,
                               std::span<const double> v, const Point& tol, double roundoff) {
  DeviationCheck out;
  std::array<double, kMaxDegree + 1> bv, bu;
  std::vector<Point> iso(static_cast<std::size_t>(s.count_u));
  const auto& off = rows.offsets();
  for (std::size_t j = 0; j < rows.size(); ++j) {
    // The iso-curve v = v_j: its control points Q_i = sum_l B_l(v_j) P_il, once per row.
    const int fv = eval_basis(s.degree_v, s.count_v, s.periodic_v, v[j], bv.data());
    for (int i = 0; i < s.count_u; ++i) {
      Point q = Point::Zero();
      for (int b = 0; b <= s.degree_v; ++b) q += bv[b] * s.at(i, wrap_index(fv + b, s.count_v));
      iso[i] = q;
    }
    const auto row = rows[j];
    for (std::size_t k = 0; k < row.size(); ++k) {
      const int fu = eval_basis(s.degree_u, s.count_u, s.periodic_u, u[off[j] + k], bu.data());
      Point p = Point::Zero();
      for (int a = 0; a <= s.degree_u; ++a) p += bu[a] * iso[wrap_index(fu + a, s.count_u)];
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
        if (ad[a] > tol[a] + roundoff) out.within = false;
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

}  // namespace sfit
