// The surface search on a sample of large data, verified on all points (sampled_search.h).
#include "sampled_search.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "fit_monitor.h"

namespace sfit::detail {

namespace {

// Pairs whose solve would cost more flops than this are not tried: the sparse factorisation
// grows as unknowns x band^2, and a pair that size is far from the fewest control points
// anyway wherever the two-stage bound leaves room (at 10^6 points, 2 % of them as control
// points cost ~4e9).
constexpr double kSolveBudget = 4e9;
// ... and at most kSolvePerPoint flops per data point of the problem (kSolveFloor at least).
// The search's columns are capped at the largest affordable nu (PairRange::affordable), so a
// costly pair only narrows a column. The pairs this leaves out are near interpolation, where
// the rules other than the paper's swing between the points anyway: on the shared sets the
// counts stayed or fell when the factor went from 2000 to 500 and the floor from 2e8 to 4e6,
// and the search's time fell by 2-5x on the largest (docs/control-points.md).
constexpr double kSolvePerPoint = 500;
constexpr double kSolveFloor = 4e6;

}  // namespace

double solve_budget(std::size_t points) {
  return std::clamp(kSolvePerPoint * static_cast<double>(points), kSolveFloor, kSolveBudget);
}

PairChoice search_on_sample(const Frame& fr, const FewRows& few, const TensorProblem& prob,
                            const TensorSpec& spec, const Point& tolerance, std::size_t step,
                            const PairRange& range, long bound, PairOracle& on_all, long& tried) {
  FitMonitor* const monitor = current_monitor();
  std::vector<double> sample_positions;
  const Rows sample = subsample(fr.centred, step, prob.positions_u(), sample_positions);
  TensorProblem sp(sample, spec, std::move(sample_positions), prob.positions_v());
  PairOracle on_sample([&](int nu, int nv) {
    if (static_cast<double>(nu) * few.nv(nv) > static_cast<double>(sample.total_points()) ||
        sp.cost(nu, few.nv(nv)) > solve_budget(sample.total_points()))
      return PairVerdict{false, HUGE_VAL};
    auto s = few.raise(solve_pair(sp, FitNorm::kL2, nu, few.nv(nv), tolerance));
    if (monitor) monitor->pair_tried(nu, nv, false);  // holding on a sample is no best
    if (!s) return PairVerdict{false, HUGE_VAL};
    return fr.judge(*s, sp.u_at(nu), sp.v_at(few.nv(nv)), nullptr, &sample);
  });
  const PairRange sample_range{sp.min_u(),
                               sp.max_u(),
                               few.min_v(sp.min_v()),
                               few.max_v(sp.max_v()),
                               [&](int nu, int nv) {
                                 return sp.cost(nu, few.nv(nv)) <=
                                        solve_budget(sample.total_points());
                               },
                               range.reach};
  const PairChoice c = search_pairs(sample_range, bound, on_sample);
  tried += on_sample.tried();
  PairChoice choice;
  if (c.nu <= 0) return choice;
  // Raise until all points hold (the smallest product first), then descend on them.
  int nu = c.nu, nv = c.nv;
  bool holds = on_all(nu, nv).holds;
  for (int k = 1; !holds && k <= 16; ++k) {
    for (const auto& [a, b] :
         {std::pair{nu + k, nv}, std::pair{nu, nv + k}, std::pair{nu + k, nv + k}}) {
      if (static_cast<long>(a) * b >= bound || a > range.max_u || b > range.max_v) continue;
      if (on_all(a, b).holds) {
        nu = a;
        nv = b;
        holds = true;
        break;
      }
    }
  }
  if (holds) {
    const auto [mu, mv] = descend(nu, nv, range, on_all);
    choice.nu = mu;
    choice.nv = mv;
    choice.stop = minimal_on_sample(step);
  }
  return choice;
}

}  // namespace sfit::detail
