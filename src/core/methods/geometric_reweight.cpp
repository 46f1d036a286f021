#include "geometric_reweight.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "parallel.h"

namespace sfit::detail {

namespace {

// Points per block of the residuals (fixed: the same values for any thread count).
constexpr std::size_t kBlock = 4096;

// e_k = |(S(u_k, v_k) - D_k) / semi| for every point of the problem; returns the largest.
double relative_residuals(const ScatteredProblem& sp, const Surface& s,
                          const std::vector<double>& u, const std::vector<double>& v,
                          const Point& inverse, std::vector<double>& e) {
  const std::vector<Point>& pts = sp.rows().points();
  const std::size_t n = pts.size(), blocks = (n + kBlock - 1) / kBlock;
  e.resize(n);
  std::vector<double> worst(blocks, 0.0);
  parallel_for(blocks, sp.spec().threads, [&](std::size_t b) {
    double w = 0;
    for (std::size_t k = b * kBlock; k < std::min(n, (b + 1) * kBlock); ++k) {
      const Point d = s.evaluate(u[k], v[k]) - pts[k];
      e[k] = d.cwiseProduct(inverse).norm();
      if (!std::isfinite(e[k])) e[k] = HUGE_VAL;
      w = std::max(w, e[k]);
    }
    worst[b] = w;
  });
  double all = 0;
  for (double w : worst) all = std::max(all, w);
  return all;
}

}  // namespace

bool reweight(const ScatteredProblem& sp, int nu, int nv, double smoothing, const Point& semi,
              Surface& s, const std::function<bool(const Surface&)>& holds) {
  const std::size_t n = sp.rows().total_points();
  if (n == 0) return false;
  const Point inverse = semi.array().inverse().matrix();
  if (!inverse.allFinite()) return false;
  const std::vector<double> u = sp.u_at(nu), v = sp.v_at(nv);
  std::vector<double> e, w(n, 1.0);
  double best = relative_residuals(sp, s, u, v, inverse, e);
  if (!std::isfinite(best) || best > kReweightReach) return false;
  std::vector<double> band;
  std::vector<Point> rhs;
  for (int round = 0; round < kReweightRounds; ++round) {
    // Lawson: w_k <- w_k e_k, normalised to mean 1, at least the floor.
    double sum = 0;
    for (std::size_t k = 0; k < n; ++k) sum += (w[k] *= e[k]);
    if (!(sum > 0)) return false;
    const double scale = static_cast<double>(n) / sum;
    for (double& x : w) x = std::max(x * scale, kReweightFloor);
    sp.assemble(nu, nv, band, rhs, w);
    Surface next;
    if (!scattered_solve(sp.spec(), nu, nv, band, rhs, smoothing, next)) return false;
    const double worst = relative_residuals(sp, next, u, v, inverse, e);
    if (!(worst < best)) return false;  // stopped falling
    best = worst;
    if (worst <= 1 && holds(next)) {
      s = std::move(next);
      return true;
    }
  }
  return false;
}

}  // namespace sfit::detail
