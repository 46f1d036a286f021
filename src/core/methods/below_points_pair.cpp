// One pair of the fallback below the points, solved and judged (below_points_pair.h).
#include "below_points_pair.h"

#include <algorithm>
#include <cmath>

#include "geometric_params.h"
#include "sfit/fold_check.h"

namespace sfit::detail {

namespace {

// The parameters are corrected where the worst point misses T by at most this factor.
constexpr double kCorrectReach = 3;
// The work of one solve at (nu, nv) over `points` points (Budget).
double solve_work(const ScatteredProblem& sp, int nu, int nv, bool calmed, std::size_t points) {
  return (calmed ? 2 : 1) * sp.cost(nu, nv) + kPointWork * static_cast<double>(points);
}

// One solve at the problem's fractions: the smoothness as the geometric search's, and lowered
// where T was missed; every point judged (the exact worst ratio). `holds`: T at every point.
Tried solve_once(const ScatteredProblem& sp, const Frame& fr, int nu, int nv,
                 const std::optional<Point>& normal, Budget& budget) {
  Tried best;
  const std::vector<double> u = sp.u_at(nu), v = sp.v_at(nv);
  const double work = solve_work(sp, nu, nv, normal.has_value(), fr.centred.total_points());
  for (double w = kSmoothing; w >= kSmoothing * kSmoothingLower; w *= kSmoothingLower) {
    Surface s;
    budget.spent += work;
    if (!sp.solve(nu, nv, w, s, normal ? kCalm : 0.0, normal ? &*normal : nullptr)) break;
    DeviationCheck c;
    const PairVerdict verdict = fr.judge(s, u, v, &c, nullptr, false);
    if (verdict.ratio < best.ratio) best = Tried{verdict.holds, verdict.ratio, std::move(s), w};
    if (verdict.holds) break;
  }
  return best;
}

}  // namespace

// One pair (below_points_pair.h).
Tried attempt(const Frame& fr, const ScatteredSpec& spec, const std::vector<double>& fu0,
              const std::vector<double>& fv0, int nu, int nv, const std::optional<Point>& normal,
              Budget& budget) {
  Tried best;
  const double pass = kPointWork * static_cast<double>(fr.centred.total_points());
  std::vector<double> fu = fu0, fv = fv0;
  for (int round = 0; round <= kCorrectionRounds; ++round) {
    const ScatteredProblem sp(fr.centred, spec, std::move(fu), std::move(fv));
    Tried t = solve_once(sp, fr, nu, nv, normal, budget);
    if (!(t.ratio < best.ratio)) break;
    t.fu = sp.fractions_u();
    t.fv = sp.fractions_v();
    t.corrections = round;
    best = std::move(t);
    // A far miss is not corrected (no round was seen to bring it within T; each costs a solve).
    if (best.holds || round == kCorrectionRounds || best.ratio > kCorrectReach) break;
    std::vector<double> u = sp.u_at(nu), v = sp.v_at(nv);
    budget.spent += pass;
    project_parameters(best.s, fr.centred, u, v, kNewtonSteps, fr.threads);
    to_fractions(best.s, u, v, fu, fv);
  }
  if (best.holds) {
    const ScatteredProblem sp(fr.centred, spec, best.fu, best.fv);
    const std::vector<double> u = sp.u_at(nu), v = sp.v_at(nv);
    // The rule's guard and no fold, at the parameters the surface was solved at.
    auto guarded = [&](const Surface& s, const std::vector<double>& su,
                       const std::vector<double>& sv) {
      return stays_near_where_covered(s, su, sv, fr.centred_box) &&
             geometric_fold(s) <= kFoldRelative * fr.box.diagonal();
    };
    best.holds = guarded(best.s, u, v);
    const double work = solve_work(sp, nu, nv, normal.has_value(), fr.centred.total_points());
    // Where the smoothness was lowered to hold T and a guard failed (a span with few points
    // swung out of the box, or the net folded): the weights in between, calmer first.
    for (double w = kSmoothing * 0.1; !best.holds && w > 1.5 * best.smoothing; w *= 0.1) {
      Surface s;
      budget.spent += work;
      if (!sp.solve(nu, nv, w, s, normal ? kCalm : 0.0, normal ? &*normal : nullptr)) break;
      const PairVerdict verdict = fr.judge(s, u, v, nullptr, nullptr, false);
      if (verdict.holds && guarded(s, u, v)) {
        best.s = std::move(s);
        best.ratio = verdict.ratio;
        best.smoothing = w;
        best.holds = true;
      } else if (!verdict.holds && verdict.ratio <= kSmoothingReach && guarded(s, u, v)) {
        // Calm and unfolded but T missed narrowly: the parameters corrected on this surface
        // and the pair solved again at this weight.
        std::vector<double> cu = u, cv = v, gu, gv;
        budget.spent += pass + work;
        project_parameters(s, fr.centred, cu, cv, kNewtonSteps, fr.threads);
        to_fractions(s, cu, cv, gu, gv);
        const ScatteredProblem again(fr.centred, spec, std::move(gu), std::move(gv));
        Surface c;
        if (!again.solve(nu, nv, w, c, normal ? kCalm : 0.0, normal ? &*normal : nullptr)) continue;
        const std::vector<double> au = again.u_at(nu), av = again.v_at(nv);
        const PairVerdict cverdict = fr.judge(c, au, av, nullptr, nullptr, false);
        if (cverdict.holds && guarded(c, au, av)) {
          best.s = std::move(c);
          best.ratio = cverdict.ratio;
          best.smoothing = w;
          best.fu = again.fractions_u();
          best.fv = again.fractions_v();
          best.corrections += 1;
          best.holds = true;
        }
      }
    }
    // Where the height alone was calmed and a guard failed: the calm term on every axis.
    if (!best.holds && normal) {
      Surface s;
      budget.spent += work;
      if (sp.solve(nu, nv, best.smoothing, s, kCalm)) {
        const PairVerdict verdict = fr.judge(s, u, v, nullptr, nullptr, false);
        if (verdict.holds && guarded(s, u, v)) {
          best.s = std::move(s);
          best.ratio = verdict.ratio;
          best.holds = true;
        }
      }
    }
  }
  return best;
}

}  // namespace sfit::detail
