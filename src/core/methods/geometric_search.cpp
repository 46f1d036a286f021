#include "geometric_search.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <map>

#include "fit_frame.h"
#include "fit_monitor.h"
#include "geometric_minimax.h"
#include "geometric_params.h"
#include "geometric_reweight.h"
#include "geometric_sample.h"
#include "pair_search.h"
#include "scattered_lsq.h"

namespace sfit::detail {

namespace {

// The smoothness term is taken for what missed where lowering its weight cuts the miss of the
// diagonal's largest pair to this fraction or less (search_geometric()). Measured at that pair:
// where it is not (a DEM at 1e-4, noisy range images at 1e-3, a LiDAR tile at 1e-2) the miss
// fell to 0.90 ... 1.0 of itself; on exact scan lines at 1e-6 to 0.56, at 1e-5 it held.
constexpr double kLowerHelps = 0.75;

// Pairs with more unknowns than this, or whose factorisation costs more flops, are not tried.
constexpr long kMaxUnknowns = kGeometricMaxUnknowns;
constexpr double kMaxCost = 4e7;

struct Attempt {
  PairVerdict verdict{false, HUGE_VAL};
  Surface s;
  double smoothing = 0;
};

// The problem's surface at (nu, nv), judged on its rows (the frame's, or a sample of them)
// with the rule's guards (judge_with_guards()): lowered smoothing where T was missed by a
// little; a fold fails the pair.
// From `start` the weight is lowered by kSmoothingLower while T is missed: always above
// kSmoothing (a weight asked for), then once where T was missed by at most kSmoothingReach.
// `reweighted`: where T is still missed by at most kReweightReach, the reweighted fit at the
// last weight (geometric_reweight.h). `probe` (not reweighted, while *probe is false): there
// the reweighted fit is tried on a copy, the pair's result left as least squares made it, and
// *probe set where it held (search_geometric(): whether the reweighted search can differ).
Attempt attempt(const ScatteredProblem& sp, const Frame& fr, const Rows* sample, int nu, int nv,
                bool reweighted, DeviationCheck* out = nullptr, double start = kSmoothing,
                bool* probe = nullptr) {
  Attempt a;
  const std::vector<double> u = sp.u_at(nu), v = sp.v_at(nv);
  if (nu < sp.min_u() || nv < sp.min_v()) return a;
  // The data term, summed once for every weight tried; its store kept per thread from pair
  // to pair (scattered_lsq.cpp keeps the factor's: new memory each pair cost page faults).
  thread_local std::vector<double> band;
  std::vector<Point> rhs;
  const std::size_t need = static_cast<std::size_t>(nu) * nv * (2 * sp.spec().degree_u + 1) *
                           (2 * sp.spec().degree_v + 1);
  if (band.capacity() < need) {
    band.clear();  // (nothing to copy)
    band.reserve(std::max(need, band.capacity() + band.capacity() / 2));
  }
  sp.assemble(nu, nv, band, rhs);
  struct GiveBack {
    ~GiveBack() {
      if (band.capacity() * sizeof(double) > kKeptStoreBytes) band = std::vector<double>();
    }
  } give_back;
  for (double w = start; w >= kSmoothing * kSmoothingLower; w *= kSmoothingLower) {
    Surface s;
    if (!scattered_solve(sp.spec(), nu, nv, band, rhs, w, s)) return a;
    const GuardedVerdict g = judge_with_guards(fr, s, u, v, out, sample);
    a = {g.verdict, std::move(s), w};
    // Within T and near the data: no lower weight is tried, folded or not.
    if (g.verdict.holds || g.folded) return a;
    if (g.verdict.ratio > kSmoothingReach && w <= kSmoothing) break;
  }
  const bool probing = !reweighted && probe && !*probe;
  if ((reweighted || probing) && fr.centred.total_points() >= kReweightPoints && !a.verdict.holds &&
      a.verdict.ratio <= kReweightReach && !a.s.control.empty()) {
    Point semi;
    for (int i = 0; i < 3; ++i)
      semi[i] = fr.tolerance[i] + (fr.tolerance[i] == 0 ? fr.roundoff : 0.0);
    const auto holds = [&](const Surface& s) {
      return judge_with_guards(fr, s, u, v, nullptr, sample).verdict.holds;
    };
    // Held with the guards (`holds`): judged again for the verdict's exact ratio and `out`.
    if (probing) {
      Surface copy = a.s;
      *probe = reweight(sp, nu, nv, a.smoothing, semi, copy, holds);
    } else if (reweight(sp, nu, nv, a.smoothing, semi, a.s, holds)) {
      a.verdict = fr.judge(a.s, u, v, out, sample, false);
    }
  }
  return a;
}

// The surfaces that held with the fewest control points (ties: all), by pair: the pair a
// search ends at is not solved again (a pair that held with more is of no further use).
using Kept = std::map<std::pair<int, int>, Attempt>;
void keep(Kept& kept, int nu, int nv, Attempt a) {
  const long n = static_cast<long>(nu) * nv;
  if (!kept.empty()) {
    const auto& [k, _] = *kept.begin();
    const long least = static_cast<long>(k.first) * k.second;
    if (n > least) return;
    if (n < least) kept.clear();
  }
  kept[{nu, nv}] = std::move(a);
}

// `near`: lowered to the control points of each pair that misses T by at most kReweightReach.
// `probe`: attempt()'s.
PairOracle oracle_for(const ScatteredProblem& sp, const Frame& fr, const Rows* sample, bool report,
                      bool reweighted, Kept* kept = nullptr, long* near = nullptr,
                      bool* probe = nullptr, double start = kSmoothing) {
  return PairOracle(
      [&sp, &fr, sample, report, reweighted, kept, near, probe, start](int nu, int nv) {
        if (static_cast<long>(nu) * nv > kMaxUnknowns || sp.cost(nu, nv) > kMaxCost ||
            static_cast<std::size_t>(nu) * nv > sp.rows().total_points())
          return PairVerdict{false, HUGE_VAL};
        Attempt a = attempt(sp, fr, sample, nu, nv, reweighted, nullptr, start, probe);
        const PairVerdict v = a.verdict;
        if (kept && v.holds) keep(*kept, nu, nv, std::move(a));
        if (near && !v.holds && v.ratio <= kReweightReach)
          *near = std::min(*near, static_cast<long>(nu) * nv);
        if (FitMonitor* m = current_monitor()) m->pair_tried(nu, nv, report && v.holds);
        return v;
      });
}

PairRange range_for(const ScatteredProblem& sp, const Rows& rows) {
  std::size_t longest = 0;
  for (std::size_t j = 0; j < rows.size(); ++j) longest = std::max(longest, rows[j].size());
  // v is no row's index: as many counts across as along (a few rows of long rows may need
  // more control points across than rows where each point has its own v).
  const int most = static_cast<int>(std::max(longest, rows.size()));
  return PairRange{sp.min_u(), std::max(sp.min_u(), most), sp.min_v(), std::max(sp.min_v(), most),
                   [&sp](int nu, int nv) {
                     return static_cast<long>(nu) * nv <= kMaxUnknowns &&
                            sp.cost(nu, nv) <= kMaxCost;
                   }};
}

long size_of(const GeometricFit& g) {
  return static_cast<long>(g.surface.count_u) * g.surface.count_v;
}

// The search over the coordinate plane nearest the best plane (geometric_params.h), below the
// count of `g` (the best plane's surface), kept in `g` where it has fewer control points.
void try_axis_plane(const Frame& fr, const FitOptions& o, long bound, int corrections, long& tried,
                    long linf_bound, long* near, double smoothing, std::optional<GeometricFit>& g) {
  if (!g) return;
  const long found = size_of(*g);
  std::optional<GeometricFit> a =
      search_geometric_counted(fr, o, std::min(bound, found), corrections, tried, BasePlane::kAxis,
                               std::min(linf_bound, found), false, near, nullptr, smoothing);
  if (a && size_of(*a) < found) {
    a->stop += "; parameters from the coordinate plane nearest the best plane";
    g = std::move(a);
  }
}

}  // namespace

std::optional<GeometricFit> search_geometric(const Frame& fr, const FitOptions& o, long bound,
                                             int corrections, long* pairs, long linf_bound) {
  long tried = 0;
  long near = LONG_MAX;  // the fewest control points of a pair the plain searches nearly held
  // Whether the reweighted fit held at a near miss of the plain search over the best plane
  // (tried there on a copy, search_geometric_counted()'s `reweight_held`; see below).
  bool reweight_held = false;
  // Whether, where nothing held, the smoothness term is what missed (see below).
  bool lower_helps = false;
  std::optional<GeometricFit> g =
      search_geometric_counted(fr, o, bound, corrections, tried, BasePlane::kBest, linf_bound,
                               false, &near, &reweight_held, kSmoothing, &lower_helps);
  // The coordinate plane's parameters, below the count found (geometric_params.h): only
  // where the best plane's found one. Where it found none below the bound the coordinate
  // plane's search was as long and found none either on every example set and generated
  // case (topobathy at 1e-3: 53 % more instructions for the whole fit, for nothing).
  try_axis_plane(fr, o, bound, corrections, tried, linf_bound, &near, kSmoothing, g);
  // The search again with the reweighted fit at near misses (geometric_reweight.h), below
  // what the plain search found: a separate search, not the plain one's oracle, because a
  // smaller pair held early can end the correction by projection at a larger count than the
  // plain search reaches (a closed tube of uneven sections: 16 x 7 against 12 x 4).
  // Only where the plain searches missed T by at most kReweightReach below their count, and
  // only where the reweighted fit held at one of the best plane's near misses: the reweighted
  // search solves the same pairs as the plain one over the best plane (the same problems,
  // bound and order) and differs from it only from the first pair where a reweighted fit holds;
  // the plain search tries the reweighting at its near misses on a copy until one holds, so
  // where none did the reweighted search would retrace the plain one and end at its count
  // (topobathy at 1e-3: no reweighted fit held at any of its 16 near misses, 169 ... 4920
  // control points, and the search cost 1.6x the fit's instructions for the same 114 x 60).
  const long found = g ? size_of(*g) : bound;
  std::optional<GeometricFit> r;
  if (near < found && reweight_held && fr.centred.total_points() >= kReweightPoints)
    r = search_geometric_counted(fr, o, bound, corrections, tried, BasePlane::kBest, 0, true);
  if (r && size_of(*r) < found) {
    r->stop += "; least squares reweighted where it missed T by a little";
    g = std::move(r);
  }
  // The searches again with the smoothness term's weight lowered from the first pair on
  // (kSmoothing x kSmoothingLower), below what they found: where what held needed the weight
  // lowered (attempt()), or where nothing held and the diagonal's largest pair, with the
  // weight lowered, held or missed by at most kLowerHelps as much (the probe in
  // search_geometric_counted()).
  // The default weight's pull on the spans that hold data does not shrink with T, and at a
  // small T it alone misses T at pairs far from the near miss attempt() lowers it at (scan
  // lines clipped by a disk at 1e-5 of the diagonal: nothing below a quarter of the points
  // held, 199 x 120 from the row rules; with the lowered weight 30 x 31). Elsewhere the search
  // is not run again: lowered from the start the weight changes the search's path, which can
  // end at a larger pair (the same clipped lines at 1e-3: 13 x 12 against 11 x 13), and where
  // nothing held for other reasons it would cost as much again for nothing (a DEM at 1e-3:
  // +55 % of the fit's CPU).
  if ((g && g->smoothing < kSmoothing) || (!g && lower_helps)) {
    const double low = kSmoothing * kSmoothingLower;
    const long before = g ? size_of(*g) : bound;
    std::optional<GeometricFit> l = search_geometric_counted(
        fr, o, before, corrections, tried, BasePlane::kBest, 0, false, nullptr, nullptr, low);
    try_axis_plane(fr, o, before, corrections, tried, 0, nullptr, low, l);
    if (l) {
      l->stop += "; the smoothness term's weight lowered from the first pair on";
      g = std::move(l);
    }
  }
  if (g) g->tried = tried;
  if (pairs) *pairs = tried;
  return g;
}

std::optional<GeometricFit> search_geometric_counted(const Frame& fr, const FitOptions& o,
                                                     long bound, int corrections, long& tried,
                                                     BasePlane plane, long linf_bound,
                                                     bool reweighted, long* near_miss,
                                                     bool* reweight_held, double smoothing,
                                                     bool* lower_helps) {
  std::optional<Fractions> f = base_surface_fractions(fr.centred, o.closed_u, o.closed_v, plane);
  if (!f) return std::nullopt;
  const ScatteredSpec spec{o.degree_u, o.degree_v, o.closed_u, o.closed_v, fr.threads};
  const std::size_t points = fr.centred.total_points();
  // Never more control points than points.
  bound = std::min<long>(bound, static_cast<long>(points));
  const std::size_t step =
      points > kSamplePoints ? (points + kSamplePoints - 1) / kSamplePoints : 1;
  std::optional<Sample> sample;
  if (step > 1) sample = take_sample(fr.centred, step);
  const Rows& srows = sample ? sample->rows : fr.centred;
  const Rows* sptr = sample ? &sample->rows : nullptr;
  std::vector<double> fu = sample ? pick(f->u, sample->index) : f->u;
  std::vector<double> fv = sample ? pick(f->v, sample->index) : f->v;
  const std::vector<double> fu0 = fu, fv0 = fv;
  // Coarse: the pair on the sample (or all points), at the base surface's parameters.
  auto sp = std::make_unique<ScatteredProblem>(srows, spec, fu, fv);
  PairRange range = range_for(*sp, srows);
  Kept kept_sp;  // of the problem *sp
  PairOracle first =
      oracle_for(*sp, fr, sptr, !sample, reweighted, &kept_sp, near_miss, reweight_held, smoothing);
  // A first bound from the diagonal (k, k), k growing by 1.5: a few small solves, after which
  // the pair search never tries a pair with more control points than it.
  long start = bound;
  int diagonal = 0, largest = 0;  // the pair that held; the largest tried
  for (int k = std::max(range.min_u, range.min_v);
       static_cast<long>(k) * k < bound && range.affordable(k, k);
       k = std::max(k + 1, static_cast<int>(k * 1.5))) {
    largest = k;
    if (first(k, k).holds) {
      start = static_cast<long>(k) * k + 1;
      diagonal = k;
      break;
    }
  }
  PairChoice c = search_pairs(range, start, first);
  if (c.nu == 0 && diagonal > 0) {
    // The pairs search_pairs() tried (its columns need not include nv = k) all failed: the
    // diagonal's pair holds, and one fewer along u or v is tried from it.
    std::tie(c.nu, c.nv) = descend(diagonal, diagonal, range, first);
    c.stop = "minimal";
  }
  tried += first.tried();
  if (c.nu == 0 && lower_helps && smoothing >= kSmoothing && largest > 0) {
    // Whether the smoothness term is what missed: the largest pair of the diagonal, with the
    // weight lowered (one solve), holds or misses by at most kLowerHelps as much. (Not the pair
    // that missed least: that can be one whose spans without data the term decides, near T for
    // other reasons; scan lines clipped by a disk at 1e-5: 31 x 151 missed by 1.29 T with
    // either weight, while 30 x 31 held with the lowered one.)
    const PairVerdict* was = first.find(largest, largest);
    const Attempt a =
        attempt(*sp, fr, sptr, largest, largest, false, nullptr, kSmoothing * kSmoothingLower);
    ++tried;
    *lower_helps = a.verdict.holds || (was && a.verdict.ratio <= kLowerHelps * was->ratio);
  }
  if (c.nu == 0) {
    // Nothing held by least squares: minimax at the nearest pairs (geometric_minimax.h).
    const GeometricLeastSquares ls = [&fr, smoothing](const ScatteredProblem& p, int nu, int nv) {
      Attempt a = attempt(p, fr, nullptr, nu, nv, false, nullptr, smoothing);
      return GeometricTry{a.verdict.holds, std::move(a.s), a.smoothing};
    };
    return geometric_minimax(fr, o, spec, *f, first, std::min(bound, linf_bound), plane, ls, tried);
  }
  int nu = c.nu, nv = c.nv;
  std::string stop = c.stop;
  // Correction: project the points onto the fit, refit, descend; while the count falls.
  int rounds = 0;
  for (int round = 0; round < corrections; ++round) {
    const auto held = kept_sp.find({nu, nv});
    const Attempt at = held != kept_sp.end() ? held->second
                                             : attempt(*sp, fr, sptr, nu, nv, reweighted, nullptr,
                                                       smoothing, reweight_held);
    if (!at.verdict.holds) break;
    std::vector<double> u = sp->u_at(nu), v = sp->v_at(nv);
    project_parameters(at.s, srows, u, v, kNewtonSteps, fr.threads);
    std::vector<double> nfu, nfv;
    to_fractions(at.s, u, v, nfu, nfv);
    auto next = std::make_unique<ScatteredProblem>(srows, spec, nfu, nfv);
    Kept kept_next;
    PairOracle o2 = oracle_for(*next, fr, sptr, !sample, reweighted, &kept_next, near_miss,
                               reweight_held, smoothing);
    if (!o2(nu, nv).holds) {
      tried += o2.tried();
      break;
    }
    const auto [a, b] = descend(nu, nv, range, o2);
    tried += o2.tried();
    if (static_cast<long>(a) * b >= static_cast<long>(nu) * nv) break;
    nu = a;
    nv = b;
    sp = std::move(next);
    kept_sp = std::move(kept_next);
    fu = std::move(nfu);
    fv = std::move(nfv);
    ++rounds;
  }
  GeometricFit out;
  out.corrections = rounds;
  std::vector<double> full_u = f->u, full_v = f->v;
  if (sample && rounds > 0) {
    carry_sample_corrections(fr.centred, sample->index, fu, fv, fu0, fv0, o.closed_u, full_u,
                             full_v);
  } else if (!sample) {
    full_u = fu;
    full_v = fv;
  }
  // Fine: verify on every point, raise until it holds, descend while one fewer holds.
  const ScatteredProblem full(fr.centred, spec, std::move(full_u), std::move(full_v));
  Kept kept;
  PairOracle all =
      oracle_for(full, fr, nullptr, true, reweighted, &kept, near_miss, reweight_held, smoothing);
  if (sample) {
    bool holds = all(nu, nv).holds;
    for (int k = 1; !holds && k <= 8; ++k) {
      for (const auto& [a, b] :
           {std::pair{nu + k, nv}, std::pair{nu, nv + k}, std::pair{nu + k, nv + k}}) {
        if (static_cast<long>(a) * b >= bound) continue;
        if (all(a, b).holds) {
          nu = a;
          nv = b;
          holds = true;
          break;
        }
      }
    }
    if (!holds) {
      tried += all.tried();
      return std::nullopt;
    }
    std::tie(nu, nv) = descend(nu, nv, range_for(full, fr.centred), all);
    stop = minimal_on_sample(step);
  }
  tried += all.tried();
  // Without a sample `full` is the problem *sp (the same points and fractions): its kept
  // surface is this pair's.
  if (!sample) kept = std::move(kept_sp);
  auto it = kept.find({nu, nv});
  const Attempt at = it != kept.end() ? std::move(it->second)
                                      : attempt(full, fr, nullptr, nu, nv, reweighted, nullptr,
                                                smoothing, reweight_held);
  if (!at.verdict.holds) return std::nullopt;
  out.surface = at.s;
  out.u = full.u_at(nu);
  out.v = full.v_at(nv);
  out.smoothing = at.smoothing;
  out.tried = tried;
  out.stop = stop;
  if (rounds > 0)
    out.stop +=
        "; parameters corrected " + std::to_string(rounds) + " time" + (rounds > 1 ? "s" : "");
  // The part of the domain the data covers (the rest decided by the smoothness term).
  const std::vector<char> cells = covered_spans(out.surface, out.u, out.v);
  const long covered = std::count(cells.begin(), cells.end(), 1);
  if (covered < static_cast<long>(cells.size()))
    out.stop += "; data in " + std::to_string(covered) + " of the " + std::to_string(cells.size()) +
                " knot spans";
  return out;
}

std::optional<GeometricFit> geometric_at_counts(const Frame& fr, const FitOptions& o, int nu,
                                                int nv, double smoothing, BasePlane plane,
                                                bool reweighted) {
  std::optional<Fractions> f = base_surface_fractions(fr.centred, o.closed_u, o.closed_v, plane);
  if (!f) return std::nullopt;
  const ScatteredSpec spec{o.degree_u, o.degree_v, o.closed_u, o.closed_v, fr.threads};
  auto sp = std::make_unique<ScatteredProblem>(fr.centred, spec, std::move(f->u), std::move(f->v));
  Attempt at = attempt(*sp, fr, nullptr, nu, nv, reweighted, nullptr, smoothing);
  if (at.s.control.empty()) return std::nullopt;
  GeometricFit g;
  g.tried = 1;
  // Where the base surface's parameters miss T, the correction (as in the search) while the
  // worst deviation falls: the pair the search chose held at corrected parameters.
  for (int round = 0; round < kCorrectionRounds && !at.verdict.holds; ++round) {
    std::vector<double> u = sp->u_at(nu), v = sp->v_at(nv);
    project_parameters(at.s, fr.centred, u, v, kNewtonSteps, fr.threads);
    std::vector<double> nfu, nfv;
    to_fractions(at.s, u, v, nfu, nfv);
    auto next = std::make_unique<ScatteredProblem>(fr.centred, spec, nfu, nfv);
    Attempt a = attempt(*next, fr, nullptr, nu, nv, reweighted, nullptr, smoothing);
    ++g.tried;
    if (a.s.control.empty() || !(a.verdict.holds || a.verdict.ratio < at.verdict.ratio)) break;
    at = std::move(a);
    sp = std::move(next);
    ++g.corrections;
  }
  g.surface = at.s;
  g.u = sp->u_at(nu);
  g.v = sp->v_at(nv);
  g.smoothing = at.smoothing;
  g.stop = "counts given";
  return g;
}

}  // namespace sfit::detail
