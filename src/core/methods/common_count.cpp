// The re-representation on a common count (common_count.h, docs/method.md 4).
#include "common_count.h"

#include <algorithm>
#include <atomic>
#include <string>

#include "parallel.h"
#include "parameters.h"
#include "sfit/error.h"

namespace sfit::detail {

namespace {

// One curve on `count` control points. At the paper's parameters: rerepresent() (docs/method.md
// 4). At positions (docs/method.md 7.4), where the curve has at least `count` points: the least
// squares fit of its points with `count` control points at the same positions, if it holds.
// Every curve's coefficients are then one linear map of its points, so curves whose points
// vary smoothly from one to the next have control points that do too, and the transverse
// stage needs few; the minimal counts differing from curve to curve would otherwise leave
// each curve's own approximation error in its control points. Where the refit does not hold
// (the count's fit is not always within the bound when a smaller one is), rerepresent().
Rerepresentation represent_one(const CurveFit& fit, std::span<const Point> points,
                               std::span<const double> positions, int degree, int count,
                               bool periodic, const Point& bound, std::span<const double> target,
                               bool weighted = false, Resampling resampling = Resampling::kPaper) {
  // A weighted curve keeps its own fit's shape: re-represented, not refitted unweighted.
  if (!weighted && fit.scaled && !positions.empty() && fit.curve.degree == degree &&
      points.size() >= static_cast<std::size_t>(count) && fit.curve.count() != count) {
    CurveFit refit;
    try {
      refit = fit_curve_with_count(points, degree, periodic, count, positions);
    } catch (const Error&) {  // singular at these positions
      refit.curve.control.clear();
    }
    if (!refit.curve.control.empty() && (refit.max_deviation.array() <= bound.array()).all() &&
        (target.empty() || std::equal(target.begin(), target.end(), refit.parameters.begin(),
                                      refit.parameters.end()))) {
      Rerepresentation r;
      r.curve = std::move(refit.curve);
      r.parameters = std::move(refit.parameters);
      r.max_deviation = refit.max_deviation;
      r.holds = true;
      return r;
    }
  }
  return rerepresent(fit, points, degree, count, periodic, bound, target, resampling);
}

}  // namespace

Represented represent(std::size_t n_curves, const PointsOf& points_of,
                      const PositionsOf& positions_of, const std::vector<CurveFit>& fits,
                      int degree, bool periodic, const Point& bound, int threads,
                      bool shared_params, std::size_t max_points,
                      std::span<const double> shared_positions,
                      std::vector<Rerepresentation>* reuse, int reuse_count,
                      const std::vector<char>* dirty, bool weighted, Resampling resampling) {
  Represented st;
  int common = degree + 1;
  for (const auto& f : fits) common = std::max(common, f.curve.count());
  st.first_common = common;
  // At positions a count above the curves' points is not worth trying: the paper's rule,
  // which fit() falls back to, does better there.
  const bool at_positions = n_curves > 0 && !positions_of(0).empty();
  const int cap =
      static_cast<int>(std::max<std::size_t>(max_points, common)) + (at_positions ? 0 : degree + 8);
  st.curves.resize(n_curves);
  while (true) {
    if (shared_params)
      st.shared_parameters =
          shared_positions.empty()
              ? paper_parameters(degree, common, periodic, static_cast<int>(max_points))
              : scaled_parameters(degree, common, periodic, shared_positions);
    // Stop the pass at the first curve that fails: the count is raised whatever the others
    // do, so the outcome (the first count at which every curve holds) is the same.
    std::atomic<bool> failed{false};
    parallel_for(n_curves, threads, [&](std::size_t i) {
      if (failed.load(std::memory_order_relaxed)) return;
      if (reuse && common == reuse_count && !(*dirty)[i]) {
        st.curves[i] = std::move((*reuse)[i]);
      } else {
        st.curves[i] =
            represent_one(fits[i], points_of(i), positions_of(i), degree, common, periodic, bound,
                          shared_params ? std::span<const double>(st.shared_parameters)
                                        : std::span<const double>(),
                          weighted, resampling);
      }
      if (!st.curves[i].holds) failed.store(true, std::memory_order_relaxed);
    });
    if (!failed.load()) break;
    if (reuse && common == reuse_count) reuse = nullptr;  // moved from: compute afresh
    if (common >= cap)
      throw Error(ErrorCode::kToleranceNotMet,
                  "re-representation cannot hold the tolerance even with " +
                      std::to_string(common) + " control points",
                  Place{}, {static_cast<double>(common)});
    ++common;
  }
  st.common = common;
  for (const auto& c : st.curves) st.repaired += c.repair_rounds > 0 ? 1 : 0;
  return st;
}

}  // namespace sfit::detail
