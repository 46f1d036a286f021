// FitOptions::counts (docs/control-points.md): the surface at exactly the pair given, with no
// search and no two-stage run: the first rule that holds (else the one closest to holding),
// minimax where least squares does not hold and the norm allows. Meant for fast refits (the
// editor's quick refit while a point is dragged).
#include <optional>
#include <string>

#include "fit_frame.h"
#include "geometric_search.h"
#include "minimax.h"
#include "search_frame.h"
#include "sfit/error.h"

namespace sfit::detail {

namespace {

// The report of a fit at given counts: within_tolerance is the per-point check's (every point
// within T per axis: the report's contract), whatever the search's further tests say; where
// one of those fails the stop reason says which, as the search would not have taken it.
// `guard`: failed_guard() of the centred surface.
void report_given(FitResult& out, const PairVerdict& verdict, const DeviationCheck& c,
                  const char* guard) {
  out.report.stop_reason = "counts given";
  out.report.within_tolerance = c.within;
  if (verdict.holds || !c.within) return;
  out.report.stop_reason +=
      std::string("; the search would not take this surface: ") +
      (guard ? std::string("its guard ") + guard + " fails"
             : std::string("a point lies farther than T from it, the axes taken together"));
}

void check_counts(const FitOptions& o) {
  const auto& c = *o.counts;
  const int lo[2] = {o.degree_u + 1, o.degree_v + 1};
  for (int a = 0; a < 2; ++a)
    if (c[a] < lo[a] || c[a] > 1000000)
      throw Error(ErrorCode::kUsage,
                  std::string("counts: ") + "uv"[a] + " count " + std::to_string(c[a]) +
                      " must be degree + 1 (" + std::to_string(lo[a]) + ") ... 1000000",
                  Place{.option = "counts"}, {static_cast<double>(c[a])});
  if (static_cast<double>(c[0]) * c[1] > 1e7)
    throw Error(ErrorCode::kUsage, "counts: more than 10^7 control points",
                Place{.option = "counts"}, {static_cast<double>(c[0]), static_cast<double>(c[1])});
}

}  // namespace

// FitOptions::counts: the surface at exactly that pair, the first rule that holds (else the
// one closest to holding); minimax where least squares does not hold and the norm allows.
FitResult fit_at_counts(const Rows& rows, const FitOptions& o, double t0,
                        std::span<const double> seam_offsets, const Centring* centring) {
  check_counts(o);
  const Frame fr = centring ? Frame(*centring, o) : Frame(rows, o);
  const int nu = (*o.counts)[0], nv = (*o.counts)[1];
  if (o.parametrization == Parametrization::kGeometric) {
    std::optional<GeometricFit> g = geometric_at_counts(fr, o, nu, nv);
    if (!g)
      throw Error(ErrorCode::kToleranceNotMet,
                  "no surface with " + std::to_string(nu) + " x " + std::to_string(nv) +
                      " control points at parameters geometric (no base surface for these "
                      "rows, or too few control points for a closed direction)",
                  Place{.option = "counts"}, {static_cast<double>(nu), static_cast<double>(nv)});
    DeviationCheck c;
    PairVerdict verdict = fr.judge(g->surface, g->u, g->v, &c);
    if (!c.within) {
      // A point beyond T: the coordinate plane's parameters (geometric_params.h), as the
      // search tries them, where their surface holds every point or misses by less. (Where
      // every point holds the best plane's surface is kept: the distributed fit's.)
      std::optional<GeometricFit> a =
          geometric_at_counts(fr, o, nu, nv, kSmoothing, BasePlane::kAxis);
      DeviationCheck ca;
      const PairVerdict va = a ? fr.judge(a->surface, a->u, a->v, &ca) : verdict;
      if (a && (ca.within || va.ratio < verdict.ratio)) {
        g = std::move(a);
        c = ca;
        verdict = va;
      }
    }
    const char* guard = failed_guard(g->surface, fr.centred_box);
    FitResult out = assemble_geometric(fr, std::move(*g), c, o);
    out.report.pairs_tried = 1;
    report_given(out, verdict, c, guard);
    out.report.seconds = now() - t0;
    return out;
  }
  std::optional<Surface> best;
  std::vector<double> best_u, best_v;
  DeviationCheck best_check;
  PairVerdict best_verdict{false, 0};
  Parametrization best_rule = Parametrization::kUniform;
  FitNorm best_norm = FitNorm::kL2;
  long tried = 0;
  for (Parametrization rule : rules_of(o.parametrization)) {
    if (rule == Parametrization::kGeometric) continue;  // above, when asked for by name
    TensorProblem prob(fr.centred, spec_of(o, rule, fr.threads, seam_offsets));
    for (FitNorm norm : {FitNorm::kL2, FitNorm::kLinf}) {
      // kL2: least squares only; kLinf: minimax (least squares only where the minimax does
      // not hold, to return a surface); kAuto: minimax where this rule's least squares
      // missed T by at most kLinfReach.
      // Weighted rows: least squares only (weights shape a least-squares fit; docs/seams.md).
      if (norm == FitNorm::kLinf && (o.norm == FitNorm::kL2 || weights_matter(rows))) continue;
      if (norm == FitNorm::kLinf && o.norm == FitNorm::kAuto &&
          (best_verdict.holds || !best || best_rule != rule || best_verdict.ratio > kLinfReach))
        continue;
      if (norm == FitNorm::kLinf && !minimax_affordable(fr.centred.total_points(), nu, nv))
        continue;
      ++tried;
      auto s = solve_pair(prob, norm, nu, nv, o.tolerance);
      if (!s) continue;
      DeviationCheck c;
      const std::vector<double> v = prob.v_at(nv);
      const PairVerdict verdict = fr.judge(*s, prob.u_at(nu), v, &c);
      if (!best || (verdict.holds && !best_verdict.holds) ||
          (verdict.holds == best_verdict.holds && verdict.ratio < best_verdict.ratio)) {
        best = std::move(s);
        best_u = prob.u_at(nu);
        best_v = v;
        best_check = c;
        best_verdict = verdict;
        best_rule = rule;
        best_norm = norm;
      }
    }
    if (best_verdict.holds) break;
  }
  if (!best)
    throw Error(ErrorCode::kToleranceNotMet,
                "no surface with " + std::to_string(nu) + " x " + std::to_string(nv) +
                    " control points: a knot span has no data",
                Place{.option = "counts"}, {static_cast<double>(nu), static_cast<double>(nv)});
  const char* guard = failed_guard(*best, fr.centred_box);
  FitResult out =
      assemble(fr, std::move(*best), std::move(best_u), std::move(best_v), best_check, o);
  out.report.parametrization = best_rule;
  out.report.norm = best_norm;
  out.report.pairs_tried = tried;
  report_given(out, best_verdict, best_check, guard);
  out.report.seconds = now() - t0;
  return out;
}

}  // namespace sfit::detail
