// The third pass's parameters: stretched where the nearest pair missed (below_points_dense.h).
#include "below_points_dense.h"

#include <algorithm>
#include <cmath>

#include "scattered_lsq.h"

namespace sfit::detail {

namespace {

// Cells of the tabulated map over [0, 1] (its slope is constant within a cell).
constexpr int kCells = 8192;

}  // namespace

std::vector<double> miss_ratios(const Frame& fr, const ScatteredSpec& spec, const Tried& t, int nu,
                                int nv) {
  const ScatteredProblem sp(fr.centred, spec, t.fu, t.fv);
  const std::vector<double> u = sp.u_at(nu), v = sp.v_at(nv);
  std::vector<double> ratio(u.size(), 0.0);
  std::size_t k = 0;
  for (const Point& p : fr.centred.points()) {
    const Point d = (t.s.evaluate(u[k], v[k]) - p).cwiseAbs();
    for (int a = 0; a < 3; ++a)
      if (fr.tolerance[a] > 0) ratio[k] = std::max(ratio[k], d[a] / fr.tolerance[a]);
    ++k;
  }
  return ratio;
}

void stretch_where_missed(const std::vector<double>& ratio, int spans, std::vector<double>& fu) {
  std::vector<double> slope(kCells, 1.0);
  const double w = 1.0 / std::max(spans, 1);  // one knot span, as a fraction of the range
  bool any = false;
  for (std::size_t k = 0; k < fu.size() && k < ratio.size(); ++k) {
    if (!(ratio[k] > 1)) continue;
    any = true;
    const double r = ratio[k];
    const int lo = std::max(0, static_cast<int>((fu[k] - 2 * w) * kCells));
    const int hi = std::min(kCells - 1, static_cast<int>((fu[k] + 2 * w) * kCells));
    for (int i = lo; i <= hi; ++i) {
      const double x = (i + 0.5) / kCells, d = std::abs(x - fu[k]);
      const double s = d <= w ? r : 1 + (r - 1) * (2 - d / w);
      slope[i] = std::max(slope[i], s);
    }
  }
  if (!any) return;
  std::vector<double> g(kCells + 1, 0.0);  // the map at the cells' edges
  for (int i = 0; i < kCells; ++i) g[i + 1] = g[i] + slope[i];
  for (double& x : g) x /= g[kCells];
  for (double& f : fu) {
    const double c = std::clamp(f, 0.0, 1.0) * kCells;
    const int i = std::min(kCells - 1, static_cast<int>(c));
    f = std::clamp(g[i] + (c - i) * (g[i + 1] - g[i]), 0.0, 1.0);
  }
}

}  // namespace sfit::detail
