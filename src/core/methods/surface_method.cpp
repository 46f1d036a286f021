// FitMethod::kSurface (docs/control-points.md): the tensor-product fit over all points at once
// (tensor_lsq.h, minimax.h), searched for the fewest nu x nv that hold (pair_search.h), in the
// frame (fit_frame.h): validated once, centred, every candidate checked at every data point
// at the full T per axis and guarded between the points; never more control points than the
// two-stage method (FitMethod::kSfit01), whose fit it starts from.
#include <algorithm>
#include <array>
#include <atomic>
#include <climits>
#include <map>
#include <optional>
#include <string>

#include "basis.h"
#include "below_points.h"
#include "count_floor.h"
#include "deviation.h"
#include "few_rows.h"
#include "fit_frame.h"
#include "fit_monitor.h"
#include "fit_registry.h"
#include "geometric_search.h"
#include "minimax.h"
#include "pair_search.h"
#include "parallel.h"
#include "row_rule_search.h"
#include "rows_at_t.h"
#include "sampled_search.h"
#include "search_frame.h"
#include "sfit/curve_fit.h"
#include "sfit/error.h"
#include "sfit/fold_check.h"
#include "surface_fitter.h"
#include "tensor_lsq.h"

namespace sfit::detail {

namespace {

bool folds(const FitResult& f, const BoundingBox& box) {
  return f.report.fold > kFoldRelative * box.diagonal();
}

}  // namespace

FitResult fit_surface_search(const FitSpec& spec) {
  const double t0 = now();
  const Rows& rows = spec.rows;  // validated and aligned by the driver (fit_driver.h)
  const FitOptions& o = spec.options;
  const std::span<const double> seam_offsets = spec.seam_offsets;
  if (o.counts) return fit_at_counts(rows, o, t0, seam_offsets, &spec.centring);

  // The two-stage fit: a pair that holds, so the bound to beat. On large data at the paper's
  // rule it runs only if the search does not beat a lower bound on its count (its rows'
  // smallest counts, sfit01_lower_bound()): it costs more than the search there (14 s against
  // a few on 10^6 ragged points at 1e-3).
  FitOptions o1 = o;
  o1.method = FitMethod::kSfit01;
  if (o1.parametrization == Parametrization::kAuto ||
      o1.parametrization == Parametrization::kGeometric)
    o1.parametrization = Parametrization::kPaper;
  const bool defer_base = rows.total_points() > kSearchPoints &&
                          o1.parametrization == Parametrization::kPaper &&
                          !(o.tolerance.array() == 0).all();
  // The method never calls another: it asks the registry for "sfit01" by name (a plug-in that
  // replaces it there replaces the bound too), on the driver's rows and centring.
  const auto two_stage = [&] {
    return method_entry("sfit01").fit(FitSpec{rows, o1, seam_offsets, spec.centring});
  };
  std::optional<FitResult> base;
  long bound = LONG_MAX, lower = 0;
  if (!defer_base) {
    base = two_stage();
    if (base->report.within_tolerance) {
      bound = static_cast<long>(base->surface.count_u) * base->surface.count_v;
      if (FitMonitor* m = current_monitor()) m->found(base->surface.count_u, base->surface.count_v);
    }
  }

  const long base_bound = bound;  // the two stages' count, before any rule's
  const Frame fr(spec.centring, o);
  const FewRows few(rows.size(), o);
  const FitOptions os = few.options(o);  // the search's problems
  std::optional<Candidate> best;
  long tried = 0;
  // At T = 0 only interpolation holds, which the two stages give with the fewest control
  // points there are (one per point and row where the data is a grid).
  const bool interpolate = (o.tolerance.array() == 0).all();
  const std::size_t points = fr.centred.total_points();
  const std::size_t step =
      points > kSearchPoints ? (points + kSearchPoints - 1) / kSearchPoints : 1;
  std::vector<Parametrization> rules = rules_of(o.parametrization);
  // The geometric rule's scattered solves cost most (on a smooth 10^6-point grid 1.4 of 2.7 s
  // CPU, for a surface no smaller; on 10^6 ragged, unevenly sampled points at 1e-3 a third of
  // the CPU, for no surface at all while the chord rule gives 13 x 11; on the 10^4-point
  // example sets half the search): it goes last, bounded by the row rules' best (the
  // 10^5-point ragged peer set keeps its surfaces at 1e-2 ... 1e-4 with 6-16 % fewer pairs
  // solved). On small data it went first, but its count never bounded the row rules there
  // (they ran with the bounds they had without it), so going last changes none of their
  // searches and only narrows its own (below twice their best, see below): every example set
  // keeps every surface at 1e-2 ... 1e-4, with up to 67 % fewer instructions
  // (iea15mw_blade_af50 at 1e-2; docs/benchmarks.md).
  std::stable_partition(rules.begin(), rules.end(),
                        [](Parametrization r) { return r != Parametrization::kGeometric; });
  // On large ragged rows the chord rule goes first: rows sampled unevenly are where the index
  // says least. On 10^6 such points at 1e-3 the uniform rule, searched first, found nothing;
  // with the chord rule first its 13 x 11 bounds the others: 66 pairs instead of 82, 1.2-1.4 s
  // of CPU instead of 1.5-1.7. (A tie now keeps the chord rule's surface.)
  bool grid = true;
  for (std::size_t j = 1; j < rows.size() && grid; ++j) grid = rows[j].size() == rows[0].size();
  if (step > 1 && !grid)
    std::stable_partition(rules.begin(), rules.end(),
                          [](Parametrization r) { return r == Parametrization::kChord; });
  // Rows (and a grid's columns) fitted as curves at T bound each rule's counts from below
  // (count_floor.h): a rule whose bound cannot beat the best, or that the sample's
  // rows are too short to reach, is not searched; where noise forces every rule to
  // interpolate the rows, no pair is searched at all.
  long floored = 0, forced_rules = 0;
  // Where the geometric rule was searched below a cap only (its rows need all their points
  // alone) and nothing held: the cap and its pairs, for the stop reason.
  long geo_capped = 0, geo_capped_pairs = 0;
  std::size_t longest = 0;
  for (std::size_t j = 0; j < rows.size(); ++j) longest = std::max(longest, rows[j].size());
  progress_phase("search", rules.size());
  FitMonitor* const monitor = current_monitor();
  std::size_t rules_done = 0;
  std::vector<Parametrization> searched;
  std::optional<GeometricFit> geo;  // the kGeometric rule's surface (geometric_search.h)
  KeptSurfaces kept;                // no pair solved twice (search_frame.h)
  // The best row rule's parameters (u per point, v per row): the winner as the search kept it
  // needs no new problem and no new pass over every point to get them.
  std::vector<double> best_u, best_v, rule_u, rule_v;
  const bool linf_may = o.norm != FitNorm::kL2 && !weights_matter(rows);
  RowRuleSearch rs{fr,   few,     o,       os, seam_offsets, step, base ? &*base : nullptr,
                   kept, monitor, linf_may};
  // Each rule's floor, made once (the geometric rule reads the chord rule's): its rows first
  // (row_floor_of(), nv at its least), its columns only where the rows do not decide (noise
  // near T on a grid: the rows' counts alone rule every row rule out).
  std::map<Parametrization, CountFloor> floors, row_floors;
  auto row_floor_of = [&](Parametrization r) -> const CountFloor& {
    if (auto it = floors.find(r); it != floors.end()) return it->second;
    auto it = row_floors.find(r);
    if (it == row_floors.end())
      it = row_floors.emplace(r, count_floor(fr.centred, os, r, fr.roundoff, FloorPart::kRows))
               .first;
    return it->second;
  };
  auto floor_of = [&](Parametrization r) -> const CountFloor& {
    auto it = floors.find(r);
    if (it == floors.end()) {
      CountFloor f = row_floor_of(r);
      f.nv = count_floor(fr.centred, os, r, fr.roundoff, FloorPart::kColumns).nv;
      it = floors.emplace(r, f).first;
    }
    return it->second;
  };
  for (Parametrization rule : rules) {
    if (rules_done > 0) progress_advance(rules_done);
    ++rules_done;
    if (interpolate) break;
    // Nothing below the bound can hold: the smallest pair is (degree + 1)^2.
    if (bound <= static_cast<long>(o.degree_u + 1) * (o.degree_v + 1)) break;
    // The paper's parameters depend on a row's length, so a sample of the row has others:
    // on large data that rule is the two-stage fit's alone.
    if (step > 1 && rule == Parametrization::kPaper) continue;
    if (rule == Parametrization::kGeometric) {
      // Its own search (scattered parameters, geometric_search.h), last: it is kept where it
      // has fewer control points than the row rules' best. On large data it is searched
      // below that best; on small data below twice it (and the two stages' count): its
      // guards and smoothing make holding less monotone than the row rules', and a search
      // below the best itself can end at a pair that fails a guard and miss a smaller one
      // (range_image_holes of bench/scan_cases.py at 1e-2: 6 x 5 below 72, none below 36).
      const long geo_limit = step == 1 && best ? std::min(base_bound, 2 * bound) : bound;
      if (!o.closed_v && rows.size() < static_cast<std::size_t>(o.degree_v) + 1) continue;
      searched.push_back(rule);
      // The rows' floor at chord-length positions (count_floor.h; a heuristic here too: a
      // surface of these parameters is no iso-curve along a row): where it cannot beat the
      // bound, or noise forces interpolation, the rule is not searched.
      // Nor where it is beyond the largest pair the rule tries (noise near T on a grid).
      // (The rows alone first: the columns' counts only raise the product.)
      const auto geometric_out = [&](const CountFloor& cf) {
        const long at_least = static_cast<long>(cf.nu) * cf.nv;
        return at_least >= geo_limit || at_least > kGeometricMaxUnknowns;
      };
      const CountFloor& crf = row_floor_of(Parametrization::kChord);
      if (geometric_out(crf) || geometric_out(floor_of(Parametrization::kChord))) {
        ++floored;
        forced_rules += crf.forced ? 1 : 0;
        continue;
      }
      // Rows that need all their points alone at T show noise beyond T only where the surface
      // restricted to a row is a curve along it; under this rule it is not (each point has its
      // own v): rows that zigzag across the plane need all their points as curves while the
      // surface through them is smooth (bench/adversarial.py's zigzag_rows: every row 80 of 80
      // points, the rule 15 x 12). There the rule is searched below a quarter of the points
      // only, a few small solves where noise does force interpolation (no smooth surface that
      // small holds); where nothing holds it counts as ruled out by its floor, but not as
      // "forced": the report says how far it was searched, and claims no noise.
      const long geo_bound =
          crf.forced ? std::min<long>(geo_limit, static_cast<long>(points / 4)) : geo_limit;
      long geo_pairs = 0;
      // Its minimax (geometric_minimax.h) only where no row rule found a pair.
      geo = search_geometric(fr, o, geo_bound, kCorrectionRounds, &geo_pairs, best ? 0 : bound);
      tried += geo_pairs;
      if (crf.forced && !geo) {
        // Not "forced": the rows' need says nothing of this rule's surfaces above the cap.
        ++floored;
        geo_capped = geo_bound;
        geo_capped_pairs = geo_pairs;
        continue;
      }
      if (geo_pairs == 0) ++floored;  // no pair of it could be tried
      const long n = geo ? static_cast<long>(geo->surface.count_u) * geo->surface.count_v : 0;
      if (!geo || n >= bound) {
        geo.reset();
      } else if (monitor) {
        monitor->found(geo->surface.count_u, geo->surface.count_v);
      }
      // Rules searched after it (registered ones on large data) search below twice its count
      // (not below its count: a tight bound can end their search at a pair that fails a
      // guard, and miss a smaller one).
      if (geo && step > 1) bound = std::min(bound, 2 * n);
      continue;
    }
    // The rows' floor alone first (nv at its least, so its product bounds the whole floor's
    // from below): where it rules the rule out, the columns are not fitted.
    const CountFloor& rf = row_floor_of(rule);
    const auto rule_out = [&](const CountFloor& f) {
      return static_cast<long>(f.nu) * f.nv >= bound ||
             (step > 1 && static_cast<std::size_t>(f.nu) > longest / step + 2 + 16);
    };
    if (rule_out(rf) || rule_out(floor_of(rule))) {
      ++floored;
      forced_rules += rf.forced ? 1 : 0;
      searched.push_back(rule);  // looked at: its floor ruled it out
      continue;
    }
    searched.push_back(rule);
    rs.tried = 0;
    std::optional<Candidate> found = search_row_rule(rs, rule, bound, rule_u, rule_v);
    tried += rs.tried;
    if (found && static_cast<long>(found->nu) * found->nv < bound) {
      bound = static_cast<long>(found->nu) * found->nv;
      best = found;
      best_u = std::move(rule_u);
      best_v = std::move(rule_v);
    }
  }
  progress_advance(rules.size());
  const bool forced =
      floored > 0 && forced_rules == floored && floored == static_cast<long>(searched.size());
  // The geometric rule's surface where no row rule gave fewer (a tie keeps the row rule's).
  if (geo && !(best && best->rule == Parametrization::kGeometric)) {
    const long n = static_cast<long>(geo->surface.count_u) * geo->surface.count_v;
    if (n < bound) {
      bound = n;
      best = Candidate{Parametrization::kGeometric, geo->norm, geo->surface.count_u,
                       geo->surface.count_v, geo->stop};
    } else {
      geo.reset();
    }
  }
  std::string deferred;
  if (defer_base) {
    if (best) {
      progress_phase("lower bound", 1);
      lower = sfit01_lower_bound(rows, o, static_cast<long>(best->nu) * best->nv);
      progress_advance(1);
    }
    if (best && static_cast<long>(best->nu) * best->nv <= lower) {
      deferred = "; at most " + std::to_string(lower) +
                 ", a lower bound on sfit01's count, so sfit01 was not run";
    } else {
      base = two_stage();
      const long base_size = static_cast<long>(base->surface.count_u) * base->surface.count_v;
      if (best && base->report.within_tolerance &&
          base_size <= static_cast<long>(best->nu) * best->nv)
        best.reset();
    }
  }
  // The two stages with all of T for the rows and columns that interpolate them (rows_at_t.h),
  // where no pair beat the two stages and theirs has more control points than there are
  // points: data that jumps from row to row. (Not where a pair of the search is kept: the
  // editor's quick refits hold a searched pair's counts, which a least-squares fit at this
  // surface's counts need not.)
  std::optional<FitResult> all_to_rows;
  if (!best && base && base->report.within_tolerance && !interpolate && !forced &&
      static_cast<std::size_t>(base->surface.count_u) * base->surface.count_v > rows.total_points())
    all_to_rows = fit_rows_at_t(spec, o1, os, *base, floor_of(o1.parametrization));
  if (!best) {
    FitResult& b = all_to_rows ? *all_to_rows : *base;
    b.report.method = FitMethod::kSfit01;
    b.report.pairs_tried = tried;
    b.report.rules_searched = searched;
    b.report.stop_reason = interpolate ? "sfit01: T = 0 interpolates"
                           : forced    ? "sfit01: the noise forces interpolation at T (every "
                                         "sampled row needs all its points), no pair searched"
                                       : "sfit01: no smaller pair held";
    // (The geometric rule searched below its cap is counted with the floored rules, but was
    // searched: its own note follows.)
    const long unsearched = floored - (geo_capped > 0 ? 1 : 0);
    if (unsearched > 0 && !forced)
      b.report.stop_reason =
          unsearched == static_cast<long>(searched.size())
              ? "sfit01: no pair searched: rows fitted alone at T need more control points "
                "than any pair the search could reach"
              : b.report.stop_reason + " (" + std::to_string(unsearched) +
                    " rules not searched: their rows at T need more control points)";
    if (geo_capped > 0)
      b.report.stop_reason +=
          "; every sampled row needs all its points alone at T, which says "
          "nothing of the geometric rule's surfaces (each point has its own "
          "v): that rule was searched below " +
          std::to_string(geo_capped) + " control points only (" + std::to_string(geo_capped_pairs) +
          " pairs) and none held";
    if (all_to_rows)
      b.report.stop_reason += "; the rows took all of T and the columns interpolate them (" +
                              std::to_string(base->surface.count_u) + " x " +
                              std::to_string(base->surface.count_v) + " with T/2 each)";
    if (rs.over_budget > 0)
      b.report.stop_reason +=
          " (" + std::to_string(rs.over_budget) + " pairs over the solve budget)";
    // Never more control points than points unless T forces it (below_points.h).
    replace_below_points(fr, o, forced, b, geo_capped == 0);
    b.report.seconds = now() - t0;
    return std::move(b);
  }
  FitResult out;
  if (best->rule == Parametrization::kGeometric) {
    DeviationCheck c;
    progress_phase("check", 1);
    fr.judge(geo->surface, geo->u, geo->v, &c);
    progress_advance(1);
    out = assemble_geometric(fr, std::move(*geo), c, o);
  } else {
    // The winner as the search kept it, else remade (deterministic: the same bits as when it
    // was judged), and checked.
    const Surface* held = kept.held({best->rule, best->norm, best->nu, best->nv});
    Surface s;
    std::vector<double> u, v;
    if (held && !best_u.empty()) {
      s = *held;
      u = std::move(best_u);
      v = std::move(best_v);
    } else {
      TensorProblem prob(fr.centred, spec_of(os, best->rule, fr.threads, seam_offsets));
      s = held ? *held
               : *few.raise(solve_pair(prob, best->norm, best->nu, few.nv(best->nv), o.tolerance));
      u = prob.u_at(best->nu);
      v = prob.v_at(few.nv(best->nv));
    }
    DeviationCheck c;
    progress_phase("check", 1);
    fr.judge(s, u, v, &c);
    progress_advance(1);
    out = assemble(fr, std::move(s), std::move(u), std::move(v), c, o);
  }
  // The fold guard (docs/seams.md): a winner that doubles back on itself between the rows
  // yields to the two stages' surface, which guards its own folds.
  if (o.fold_guard && folds(out, fr.box)) {
    progress_phase("fold guard", 1);
    if (!base) base = two_stage();
    if (base->report.within_tolerance && base->report.fold < out.report.fold) {
      FitResult& b = *base;
      b.report.method = FitMethod::kSfit01;
      b.report.pairs_tried = tried;
      b.report.rules_searched = searched;
      b.report.stop_reason = "sfit01: the search's " + std::to_string(best->nu) + " x " +
                             std::to_string(best->nv) + " folds more between the rows";
      replace_below_points(fr, o, false, b);
      b.report.seconds = now() - t0;
      return std::move(b);
    }
  }
  FitReport& r = out.report;
  r.parametrization = best->rule;
  r.norm = best->norm;
  r.pairs_tried = tried;
  r.rules_searched = std::move(searched);
  r.stop_reason = best->stop + deferred;
  if (rs.over_budget > 0)
    r.stop_reason += " (" + std::to_string(rs.over_budget) + " pairs over the solve budget)";
  if (base) {
    r.row_counts = std::move(base->report.row_counts);
    r.column_counts = std::move(base->report.column_counts);
    r.raised_u = base->report.raised_u;
    r.raised_v = base->report.raised_v;
    r.repaired_rows = base->report.repaired_rows;
    r.repaired_columns = base->report.repaired_columns;
    r.solves = base->report.solves;
  }
  r.seconds = now() - t0;
  return out;
}

}  // namespace sfit::detail
