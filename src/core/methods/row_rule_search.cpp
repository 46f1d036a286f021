// One row rule's search of the surface method (row_rule_search.h).
#include "row_rule_search.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "fit_monitor.h"
#include "minimax.h"
#include "pair_search.h"
#include "sampled_search.h"
#include "tensor_lsq.h"

namespace sfit::detail {

namespace {

// Minimax fits per rule in the search (each is a linear program per axis).
constexpr int kLinfTries = 2;

}  // namespace

std::optional<Candidate> search_row_rule(RowRuleSearch& rs, Parametrization rule, long bound,
                                         std::vector<double>& u, std::vector<double>& v) {
  const Frame& fr = rs.fr;
  const FitOptions& o = rs.o;
  const FitOptions& os = rs.os;
  rs.kept.next_rule();
  TensorProblem prob(fr.centred, spec_of(os, rule, fr.threads, rs.seam_offsets));
  // The last descent tries two fewer too where one fewer fails: on the example sets that
  // lowers d150_wing at 1e-3 from 9 x 4 to 7 x 4 and height_field at 1e-3 from 17 x 22 to
  // 17 x 20, for two more solves at most per rule (docs/control-points.md).
  const PairRange range{prob.min_u(),
                        prob.max_u(),
                        rs.few.min_v(prob.min_v()),
                        rs.few.max_v(prob.max_v()),
                        [&](int nu, int nv) {
                          return prob.cost(nu, rs.few.nv(nv)) <=
                                 solve_budget(fr.centred.total_points());
                        },
                        2};
  PairOracle l2([&](int nu, int nv) {
    // More control points than points leave the system singular.
    if (static_cast<double>(nu) * rs.few.nv(nv) > static_cast<double>(fr.centred.total_points()))
      return PairVerdict{false, HUGE_VAL};
    if (prob.cost(nu, rs.few.nv(nv)) > solve_budget(fr.centred.total_points())) {
      ++rs.over_budget;
      return PairVerdict{false, HUGE_VAL};
    }
    std::optional<Surface> ls = solve_pair(prob, FitNorm::kL2, nu, rs.few.nv(nv), o.tolerance);
    const bool refinable =
        ls && rs.linf_may && minimax_affordable(fr.centred.total_points(), nu, nv);
    auto s = rs.few.raise(refinable ? ls : std::move(ls));
    const PairVerdict verdict =
        s ? fr.judge(*s, prob.u_at(nu), prob.v_at(rs.few.nv(nv))) : PairVerdict{false, HUGE_VAL};
    if (verdict.holds) {
      rs.kept.keep_held({rule, FitNorm::kL2, nu, nv}, *s);
    } else if (refinable && verdict.ratio <= kLinfReach) {
      rs.kept.keep_ls(nu, nv, *ls);
    }
    if (rs.monitor) rs.monitor->pair_tried(nu, nv, verdict.holds);
    return verdict;
  });
  PairChoice choice;
  if (rs.step == 1) {
    choice = search_pairs(range, bound, l2);
  } else {
    choice = search_on_sample(fr, rs.few, prob, spec_of(os, rule, fr.threads, rs.seam_offsets),
                              o.tolerance, rs.step, range, bound, l2, rs.tried);
  }
  rs.tried += l2.tried();
  std::optional<Candidate> found;
  if (choice.nu > 0) found = Candidate{rule, FitNorm::kL2, choice.nu, choice.nv, choice.stop};
  if (rs.linf_may) {
    // Minimax from the least-squares choice (or the two-stage pair) downwards, at pairs
    // where least squares missed T by a little (kAuto) or at all (kLinf).
    PairOracle linf([&](int nu, int nv) {
      auto s = rs.few.raise(
          solve_pair(prob, FitNorm::kLinf, nu, rs.few.nv(nv), o.tolerance, rs.kept.ls(nu, nv)));
      const PairVerdict verdict =
          s ? fr.judge(*s, prob.u_at(nu), prob.v_at(rs.few.nv(nv))) : PairVerdict{false, HUGE_VAL};
      if (verdict.holds) rs.kept.keep_held({rule, FitNorm::kLinf, nu, nv}, *s);
      if (rs.monitor) rs.monitor->pair_tried(nu, nv, verdict.holds);
      return verdict;
    });
    int linf_left = kLinfTries;
    auto worth = [&](int nu, int nv) {
      if (!minimax_affordable(fr.centred.total_points(), nu, nv)) return false;
      if (linf.known(nu, nv)) return true;
      if (linf_left <= 0) return false;
      if (o.norm == FitNorm::kLinf) return true;
      const PairVerdict& v = l2(nu, nv);
      if (v.holds || v.ratio > kLinfReach) return false;
      --linf_left;
      return true;
    };
    int nu = found ? found->nu : rs.base ? rs.base->surface.count_u : 0;
    int nv = found ? found->nv : rs.base ? rs.base->surface.count_v : 0;
    if (!found && (!rs.base || rs.base->report.parametrization != rule))
      nu = 0;  // none of the rule
    // kAuto solves at most kLinfTries minimax pairs per rule, so its descent takes at most
    // that many steps: where even those cannot go below the best, it is not started.
    const long reach =
        std::min({static_cast<long>(nu - kLinfTries) * nv,
                  static_cast<long>(nu) * (nv - kLinfTries), static_cast<long>(nu - 1) * (nv - 1)});
    if (o.norm == FitNorm::kAuto && reach >= bound) nu = 0;
    if (nu > 0) {
      const auto [mu, mv] = descend(nu, nv, range, linf, worth);
      if (static_cast<long>(mu) * mv < static_cast<long>(nu) * nv) {
        found = Candidate{rule, FitNorm::kLinf, mu, mv,
                          o.norm == FitNorm::kLinf ? "minimal"
                                                   : "minimal (minimax tried "
                                                     "where least squares missed "
                                                     "T by up to 25 %)"};
      }
    }
    rs.tried += linf.tried();
  }
  if (found && static_cast<long>(found->nu) * found->nv < bound) {
    u = prob.u_at(found->nu);  // (its moments are cached: it was judged on all points)
    v = prob.v_at(rs.few.nv(found->nv));
  }
  return found;
}

}  // namespace sfit::detail
