// The curve stage's count searches (curve_stage.h, docs/method.md 3).
#include "curve_stage.h"

#include <algorithm>

#include "parallel.h"

namespace sfit::detail {

namespace {
constexpr std::size_t kBlock = 16;  // curves whose searches chain their starting counts
}  // namespace

std::size_t fit_curves(std::size_t n_curves, const PointsOf& points_of,
                       const PositionsOf& positions_of, const CurveFitOptions& base,
                       const std::vector<int>& hints, int threads, std::vector<CurveFit>& fits,
                       const std::vector<char>* todo, const WeightsOf& weights_of) {
  const bool have_hints = hints.size() == n_curves;
  const std::size_t n_blocks = (n_curves + kBlock - 1) / kBlock;
  fits.resize(n_curves);
  std::vector<std::size_t> fitted(n_blocks, 0);
  // The starting count a fit passes on to the next curve of its block.
  auto passes_on = [&](const CurveFit& f, int previous) {
    return f.curve.degree == base.degree && !f.curve.control.empty() ? f.curve.count() : previous;
  };
  parallel_for(n_blocks, threads, [&](std::size_t b) {
    int previous = 0;      // the hint this pass gives the next curve
    int previous_old = 0;  // the hint the earlier pass gave it
    for (std::size_t i = b * kBlock; i < std::min(n_curves, (b + 1) * kBlock); ++i) {
      const bool must = !todo || (*todo)[i] || (!have_hints && previous != previous_old);
      if (todo) previous_old = passes_on(fits[i], previous_old);
      if (must) {
        CurveFitOptions co = base;
        co.hint = have_hints ? hints[i] : previous;
        co.positions = positions_of(i);
        if (weights_of) co.weights = weights_of(i);  // weighted least squares
        fits[i] = fit_curve(points_of(i), co);
        ++fitted[b];
        if (FitMonitor* m = current_monitor()) m->step();
      }
      previous = passes_on(fits[i], previous);
    }
  });
  std::size_t n = 0;
  for (std::size_t f : fitted) n += f;
  return n;
}

// The common count is the largest count of any curve, so that one must be the paper's: the
// smallest count that holds (CountSearch::kLinear). The fast search gives a count c that
// holds while c - 1 fails; the smallest count that holds is <= c. Going through the curves
// by decreasing fast count, a curve whose fast count is above the largest linear count found
// so far gets the linear search; the first whose fast count is not stops the pass, since
// neither it nor any after it can raise the maximum. The result: the maximum (and so the
// surface's count) equals the linear search's, at the cost of about one linear search
// (README "Count search"). Bounded: a scan that would cost more point-solves than
// kExactMaximumBudget times the stage's points stops the pass (the fast counts stay), so a
// single row of 10^6 points needing 1000 control points is not searched one count at a time.
void exact_maximum(std::vector<CurveFit>& fits, const PointsOf& points_of,
                   const PositionsOf& positions_of, const CurveFitOptions& base, int threads,
                   const WeightsOf& weights_of) {
  if (base.search != CountSearch::kFast) return;
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < fits.size(); ++i)
    if (fits[i].curve.degree == base.degree) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return fits[a].curve.count() > fits[b].curve.count();
  });
  int largest = 0;
  CurveFitOptions linear = base;
  linear.search = CountSearch::kLinear;
  constexpr double kExactMaximumBudget = 32;
  double budget = 0;
  for (std::size_t i = 0; i < fits.size(); ++i)
    budget += kExactMaximumBudget * static_cast<double>(points_of(i).size());
  auto cost_of = [&](std::size_t i) {
    return static_cast<double>(fits[i].curve.count() - base.degree) *
           static_cast<double>(points_of(i).size());
  };
  // The pass is sequential (each linear count can end it), so the next `threads` curves it
  // would visit if none ended it are searched at once, and their results are then taken in
  // order under the same rule; a search the rule does not reach is dropped. Same result as
  // one curve at a time, for any thread count.
  const std::size_t batch = static_cast<std::size_t>(std::max(1, threads));
  std::vector<std::size_t> next;
  std::vector<CurveFit> linear_fits;
  for (std::size_t k = 0; k < order.size();) {
    next.clear();
    double left = budget;
    for (std::size_t m = k; m < order.size() && next.size() < batch; ++m) {
      const std::size_t i = order[m];
      if (fits[i].curve.count() <= largest || cost_of(i) > left) break;
      left -= cost_of(i);
      next.push_back(i);
    }
    if (next.empty()) return;
    linear_fits.assign(next.size(), CurveFit{});
    parallel_for(next.size(), threads, [&](std::size_t c) {
      CurveFitOptions o = linear;
      o.positions = positions_of(next[c]);
      if (weights_of) o.weights = weights_of(next[c]);
      linear_fits[c] = fit_curve(points_of(next[c]), o);
    });
    for (std::size_t c = 0; c < next.size(); ++c) {
      const std::size_t i = next[c];
      if (fits[i].curve.count() <= largest || cost_of(i) > budget) return;
      budget -= cost_of(i);
      linear_fits[c].solves += fits[i].solves;
      fits[i] = std::move(linear_fits[c]);
      largest = std::max(largest, fits[i].curve.count());
    }
    k += next.size();
  }
}

}  // namespace sfit::detail
