// Tensor-product least squares on given knot vectors (knot_tensor_lsq.h).
#include "knot_tensor_lsq.h"

#include <algorithm>
#include <cstddef>

#include "banded_lsq.h"
#include "basis_knots.h"

namespace sfit::detail {

bool knot_tensor_lsq(const Rows& rows, const std::vector<double>& u, const std::vector<double>& v,
                     const Point& centre, const KnotVector& ku, int p, int nu, const KnotVector& kv,
                     int q, int nv, double ridge, Surface& s) {
  const int n = nu * nv, w = std::min(n, p * nv + q + 1);
  const bool per = ku.periodic();
  const int ru = p >= 2 ? 2 : 1, rv = q >= 2 ? 2 : 1;
  // Equations as (first unknown, kind, index): kind 0 a point, 1 u smoothing, 2 v smoothing.
  struct Eq {
    int first, kind;
    std::size_t index;
  };
  std::vector<Eq> eqs;
  eqs.reserve(rows.total_points() + 2 * static_cast<std::size_t>(n));
  std::vector<double> Nu(static_cast<std::size_t>(p + 1)), Nv(static_cast<std::size_t>(q + 1));
  std::vector<std::size_t> row_of(rows.total_points());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const int fv = eval_basis(kv, q, nv, false, v[j], Nv.data());
    for (std::size_t k = rows.offsets()[j]; k < rows.offsets()[j + 1]; ++k) {
      row_of[k] = j;
      eqs.push_back({eval_basis(ku, p, nu, per, u[k], Nu.data()) * nv + fv, 0, k});
    }
  }
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const std::size_t at = static_cast<std::size_t>(i * nv + j);
      if (per || i + ru < nu) eqs.push_back({i * nv + j, 1, at});
      if (j + rv < nv) eqs.push_back({i * nv + j, 2, at});
    }
  std::stable_sort(eqs.begin(), eqs.end(),
                   [](const Eq& a, const Eq& b) { return a.first < b.first; });
  BandedLeastSquares ls(n, w, per);
  std::vector<double> coef(static_cast<std::size_t>(w));
  for (const Eq& e : eqs) {
    const int start = per ? e.first % n : std::min(e.first, std::max(0, n - w));
    const std::size_t o = per ? 0 : static_cast<std::size_t>(e.first - start);
    std::fill(coef.begin(), coef.end(), 0.0);
    if (e.kind == 0) {
      eval_basis(ku, p, nu, per, u[e.index], Nu.data());
      eval_basis(kv, q, nv, false, v[row_of[e.index]], Nv.data());
      for (int a = 0; a <= p; ++a)
        for (int b = 0; b <= q; ++b) coef[o + static_cast<std::size_t>(a * nv + b)] = Nu[a] * Nv[b];
      ls.add(start, coef.data(), rows.points()[e.index] - centre, 1);
    } else {
      const std::size_t step = e.kind == 1 ? static_cast<std::size_t>(nv) : 1;
      const int r = e.kind == 1 ? ru : rv;
      coef[o] = 1;
      coef[o + step] = r == 2 ? -2 : -1;
      if (r == 2) coef[o + 2 * step] = 1;
      ls.add(start, coef.data(), Point::Zero(), ridge);
    }
  }
  std::vector<Point> x;
  if (!ls.solve(x)) return false;
  s = Surface();
  s.degree_u = p;
  s.degree_v = q;
  s.count_u = nu;
  s.count_v = nv;
  s.periodic_u = per;
  s.set_knots_u(ku);
  s.set_knots_v(kv);
  s.control.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    if (!x[static_cast<std::size_t>(k)].allFinite()) return false;
    s.control[static_cast<std::size_t>(k)] = x[static_cast<std::size_t>(k)] + centre;
  }
  return true;
}

}  // namespace sfit::detail
