#include "minimax.h"

#include <ClpSimplex.hpp>
#include <CoinPackedMatrix.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "basis_knots.h"

namespace sfit::detail {

namespace {

constexpr int kRounds = 40;  // exchange rounds; each adds the points the last LP missed
// minimax_refine_points(): a coefficient whose data term (the sum of its basis values over the
// points) is below this fraction of the mean keeps its least-squares value.
constexpr double kWeakHold = 0.05;
// refine() per point (the geometric rule): the exchange's points, per unknown, beyond which it
// gives up. Where the minimax surface held (the noisy range images of bench/scan_cases.py at
// 1e-3, noise 0.9 T, seeds 3 and 7), the exchange ended with at most 9.2 points per unknown;
// on a LiDAR tile (jumps at roofs and trees, seed 7 at 1e-2) its error crept up to T over 26
// rounds and 9,400 points (26 per unknown) for 361 unknowns, 45 s of CPU, and missed.
constexpr std::size_t kPointsPerUnknown = 12;

// The design of one point: (pu + 1)(pv + 1) unknowns and their basis products.
struct Design {
  int width = 0;
  std::vector<int> index;     // points x width
  std::vector<double> value;  // points x width
};

// v_per_point: v holds one parameter per point (the geometric rule's), else one per row.
Design design_of(const Rows& rows, const std::vector<double>& u, const std::vector<double>& v,
                 const Surface& s, bool v_per_point) {
  Design d;
  const int wu = s.degree_u + 1, wv = s.degree_v + 1;
  d.width = wu * wv;
  const std::size_t N = rows.total_points();
  d.index.resize(N * d.width);
  d.value.resize(N * d.width);
  std::array<double, kMaxDegree + 1> bu, bv;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    int fv = v_per_point ? 0 : basis_v(s, v[j], bv.data());
    for (std::size_t k = rows.offsets()[j]; k < rows.offsets()[j + 1]; ++k) {
      if (v_per_point) fv = basis_v(s, v[k], bv.data());
      const int fu = basis_u(s, u[k], bu.data());
      int c = 0;
      for (int a = 0; a < wu; ++a)
        for (int b = 0; b < wv; ++b, ++c) {
          d.index[k * d.width + c] =
              wrap_index(fu + a, s.count_u) * s.count_v + wrap_index(fv + b, s.count_v);
          d.value[k * d.width + c] = bu[a] * bv[b];
        }
    }
  }
  return d;
}

// Residuals S - D on axis `axis` of every point for coefficients x.
void residuals(const Design& d, const std::vector<double>& x, const std::vector<double>& data,
               std::vector<double>& r) {
  const std::size_t N = data.size();
  r.resize(N);
  for (std::size_t k = 0; k < N; ++k) {
    double s = 0;
    for (int c = 0; c < d.width; ++c) s += d.value[k * d.width + c] * x[d.index[k * d.width + c]];
    r[k] = s - data[k];
  }
}

// The minimax coefficients of one axis, from x (least squares) in place. False when the
// minimax error is above `tol` (the LP of a subset already proves it).
// `keep_weak`: the coefficients the data hold weakly (kWeakHold) keep their least-squares
// values, which the smoothness term made: the LP has none, and a coefficient that no point
// holds (a hole, an empty corner) would go wherever the simplex leaves it (on
// range_hole_noise of bench/scan_cases.py: a minimax 19 x 19 within T at the points swung out
// of the box and folded over the hole).
bool minimax_axis(const Design& d, std::vector<double>& x, const std::vector<double>& data,
                  double tol, bool keep_weak, std::size_t most_points) {
  const std::size_t N = data.size();
  const int n = static_cast<int>(x.size());
  std::vector<double> r;
  residuals(d, x, data, r);
  double worst = 0;
  for (double e : r) worst = std::max(worst, std::abs(e));
  if (worst <= tol) return true;  // least squares holds this axis already
  // The LP in units of a power of two near the worst residual where that is far from 1 (data
  // of size 1e100 or 1e-100): CLP asserts on bounds beyond 1e100 and works to absolute
  // tolerances. A power of two scales exactly; data of ordinary size keeps its LP, bit for bit.
  const int e = std::ilogb(worst);
  const double unit = e > 32 || e < -32 ? std::ldexp(1.0, e) : 1.0;
  // Unknowns: the change dx of the coefficients (free), and t >= 0; minimise t.
  ClpSimplex lp;
  lp.setLogLevel(0);
  std::vector<double> col_lo(n + 1, -COIN_DBL_MAX), col_hi(n + 1, COIN_DBL_MAX), obj(n + 1, 0.0);
  if (keep_weak) {
    // The data's hold on each coefficient: the sum of its basis values over the points.
    std::vector<double> held(n, 0.0);
    for (std::size_t k = 0; k < d.value.size(); ++k) held[d.index[k]] += d.value[k];
    const double mean = std::accumulate(held.begin(), held.end(), 0.0) / n;
    for (int i = 0; i < n; ++i)
      if (held[i] < kWeakHold * mean) col_lo[i] = col_hi[i] = 0.0;
  }
  col_lo[n] = 0.0;
  col_hi[n] = COIN_DBL_MAX;
  obj[n] = 1.0;
  CoinPackedMatrix empty(false, 0, 0);
  empty.setDimensions(0, n + 1);
  lp.loadProblem(empty, col_lo.data(), col_hi.data(), obj.data(), nullptr, nullptr);
  const std::vector<double> r0 = r;
  std::vector<char> active(N, 0);
  std::vector<std::size_t> order(N);
  std::vector<int> idx;
  std::vector<double> val;
  std::vector<CoinBigIndex> starts;
  std::vector<double> lo, hi;
  // Adds the points `add` as two rows each: r0 + A dx - t <= 0 and r0 + A dx + t >= 0.
  auto add_rows = [&](const std::vector<std::size_t>& add) {
    idx.clear();
    val.clear();
    starts.assign(1, 0);
    lo.clear();
    hi.clear();
    for (std::size_t k : add) {
      for (int sign : {-1, 1}) {
        for (int c = 0; c < d.width; ++c) {
          idx.push_back(d.index[k * d.width + c]);
          val.push_back(d.value[k * d.width + c]);
        }
        idx.push_back(n);
        val.push_back(sign);
        starts.push_back(static_cast<CoinBigIndex>(idx.size()));
        lo.push_back(sign < 0 ? -COIN_DBL_MAX : -r0[k] / unit);
        hi.push_back(sign < 0 ? -r0[k] / unit : COIN_DBL_MAX);
      }
      active[k] = 1;
    }
    lp.addRows(static_cast<int>(lo.size()), lo.data(), hi.data(), starts.data(), idx.data(),
               val.data());
  };
  // Start: the points least squares fits worst, 2 per unknown (at least 64).
  std::iota(order.begin(), order.end(), std::size_t{0});
  const std::size_t first = std::min<std::size_t>(N, std::max<std::size_t>(64, 2 * n));
  std::partial_sort(
      order.begin(), order.begin() + first, order.end(),
      [&](std::size_t a, std::size_t b) { return std::abs(r0[a]) > std::abs(r0[b]); });
  add_rows(std::vector<std::size_t>(order.begin(), order.begin() + first));
  std::vector<double> dx(n, 0.0), xt(n);
  for (int round = 0; round < kRounds; ++round) {
    lp.dual();
    if (!lp.isProvenOptimal()) lp.primal();
    if (!lp.isProvenOptimal()) return false;
    const double* sol = lp.primalColumnSolution();
    const double t = sol[n] * unit;
    if (t > tol) return false;  // a subset's minimax error bounds the whole's from below
    for (int i = 0; i < n; ++i) xt[i] = x[i] + sol[i] * unit;
    residuals(d, xt, data, r);
    std::vector<std::size_t> missed;
    double all = 0;
    for (std::size_t k = 0; k < N; ++k) {
      all = std::max(all, std::abs(r[k]));
      if (!active[k] && std::abs(r[k]) > t) missed.push_back(k);
    }
    if (missed.empty()) {  // every point within t: t is the minimax error of them all
      x = xt;
      return true;
    }
    // Past the budget the exchange gives up: not shown to hold (false), as a subset above T.
    if (std::count(active.begin(), active.end(), 1) >= static_cast<long>(most_points)) return false;
    const std::size_t take = std::min<std::size_t>(missed.size(), std::max<std::size_t>(32, n));
    std::partial_sort(
        missed.begin(), missed.begin() + take, missed.end(),
        [&](std::size_t a, std::size_t b) { return std::abs(r[a]) > std::abs(r[b]); });
    missed.resize(take);
    add_rows(missed);
  }
  return false;
}

bool refine(const Rows& rows, const std::vector<double>& u, const std::vector<double>& v,
            bool v_per_point, const Point& tolerance, Surface& s) {
  const Design d = design_of(rows, u, v, s, v_per_point);
  const std::size_t n = s.control.size();
  for (int a = 0; a < 3; ++a) {
    std::vector<double> x(n), data(rows.total_points());
    for (std::size_t i = 0; i < n; ++i) x[i] = s.control[i][a];
    for (std::size_t k = 0; k < data.size(); ++k) data[k] = rows.points()[k][a];
    // Per point (the geometric rule): the LP's points at most kPointsPerUnknown per unknown.
    const std::size_t most = v_per_point ? kPointsPerUnknown * n : data.size();
    if (!minimax_axis(d, x, data, tolerance[a], v_per_point, most)) return false;
    for (std::size_t i = 0; i < n; ++i) s.control[i][a] = x[i];
  }
  return true;
}

}  // namespace

bool minimax_refine(const Rows& rows, const std::vector<double>& u, const std::vector<double>& v,
                    const Point& tolerance, Surface& s) {
  return refine(rows, u, v, false, tolerance, s);
}

bool minimax_refine_points(const Rows& rows, const std::vector<double>& u,
                           const std::vector<double>& v, const Point& tolerance, Surface& s) {
  return refine(rows, u, v, true, tolerance, s);
}

bool minimax_affordable(std::size_t points, int nu, int nv) {
  // Measured: an LP of 10^4 points and 250 unknowns takes CLP ~0.5 s per axis, and one of
  // 578 points and 200 unknowns ~0.1 s (which made a 0.03 s fit 1.5 s for nothing).
  const double n = static_cast<double>(nu) * nv;
  return n <= 100 && n * static_cast<double>(points) <= 3e4;
}

}  // namespace sfit::detail
