// The surface search's last resort below the points (below_points.h).
#include "below_points.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <vector>

#include <Eigen/Eigenvalues>

#include "below_points_dense.h"
#include "below_points_pair.h"
#include "fit_frame.h"
#include "fit_monitor.h"
#include "geometric_params.h"
#include "scattered_lsq.h"
#include "sfit/fold_check.h"

namespace sfit::detail {

namespace {

// Bisection steps on the product (each halves the interval: 2^-8 of the points at the end).
constexpr int kBisections = 8;
// Where the largest product fails, so many smaller ones (each 0.8 of the last) are tried
// before giving up: a guard (the fold, the calm) can fail at one pair and pass at a smaller.
// Only where the top held T at every point but failed the guard or folded.
constexpr int kTopTries = 3;
// The fallback's work budget (Budget), in flops: kWorkFloor, or kWorkPerPoint for each data
// point where that is more (a few seconds; about what the search before it costs on such data).
constexpr double kWorkFloor = 1.5e10;
constexpr double kWorkPerPoint = 2e4;
// New pairs the descent from the bisection's pair may solve.
constexpr long kDescentTries = 6;
// The ladder runs where the nearest pair tried so far missed T by at most this factor: the
// pairs that hold are not monotone in the product, but no smaller pair was seen to come from
// a far miss to within T (two-point rows on a wave: the largest pairs miss by 1.06 ... 1.27x
// and the ladder finds pairs that hold; the LiDAR strip at 1e-3: 14.9x, and 49 ladder pairs
// came no nearer than 10.6x; the LiDAR tile at 1e-3: 16.8x, and the ladder spent 12 s of
// the budget on 9 pairs, none nearer).
constexpr double kLadderReach = 3;

}  // namespace

namespace {

// The smoothness of the plane's coordinates in the warped pass (attempt()'s `plane`): the
// calm term's weight, so the columns, zigzagging in the plane by half the rows' warps, are
// straightened by the net rather than followed.
constexpr double kWarpedPlane = kCalm;

// The warped pass runs where the first pass's nearest pair missed T by at most this factor
// (or where none missed: they held T but failed a guard, or made no surface). Measured on
// the LiDAR strip: it brought first-pass misses of 3.4 ... 4.0x (1e-2) within T, and misses
// of 10 ... 40x (1e-3) only to 5 ... 35x, at about 2 s a fit.
constexpr double kWarpReach = 2 * kLadderReach;

// The stretched pass's rounds (each from the last one's nearest pair, while it missed fewer).
constexpr int kDenseRounds = 3;

// The nearest pair a pass tried that did not hold (its miss, the surface and fractions).
struct Nearest {
  double ratio = -1;  // -1: no pair tried (no base surface, or none affordable)
  int nu = 0, nv = 0;
  Tried t;
};

// One pass of the fallback from the fractions of `st` (nullopt: no base surface); `label`
// names its parameters in the stop reason (empty for the base plane's).
std::optional<GeometricFit> search(const Frame& fr, long points, std::optional<Setup> st,
                                   const std::string& label, double plane, bool calmer,
                                   std::string& why, Budget& budget, Nearest& nearest);

}  // namespace

bool holds_below_points(const Frame& fr, const FitOptions& o, int nu, int nv, bool warped) {
  const std::optional<Setup> st = prepare(fr, o, warped);
  if (!st) return false;
  const ScatteredProblem sp(fr.centred, st->spec, st->f.u, st->f.v);
  if (nu < sp.min_u() || nv < sp.min_v()) return false;
  Budget unlimited{HUGE_VAL};
  return attempt(fr, st->spec, st->f.u, st->f.v, nu, nv, st->normal, unlimited,
                 warped && st->normal ? kWarpedPlane : 0)
      .holds;
}

std::optional<GeometricFit> fit_below_points(const Frame& fr, const FitOptions& o, long points,
                                             std::string& why, double work) {
  Budget budget{work > 0 ? work
                         : std::max(kWorkFloor, kWorkPerPoint * static_cast<double>(points))};
  Nearest first, warped;
  std::optional<GeometricFit> g =
      search(fr, points, prepare(fr, o, false), "", 0, false, why, budget, first);
  // Where nothing held from the base plane's parameters, an open sheet's u warped by the
  // rows' chord length, in what is left of the same budget.
  if (g || budget.over() || o.closed_u || o.closed_v) return g;
  // (Not where no pair could be tried: the warped pass has the same base and the same costs.)
  const double nearest = first.ratio;
  if (nearest < 0) return g;
  std::string note;
  std::optional<Setup> st;
  if (!(nearest > kWarpReach && nearest < HUGE_VAL)) {
    st = prepare(fr, o, true);
    const double plane = st && st->normal ? kWarpedPlane : 0;
    g = search(fr, points, std::move(st), " (u warped by the rows' chord length)", plane, false,
               note, budget, warped);
    if (g) return g;
    why += "; with u warped by the rows' chord length: " + note;
  }
  // Then the base plane's fractions (as the first pass's nearest pair corrected them)
  // stretched where that pair missed T (below_points_dense.h), again from each round's nearest
  // pair while it misses T by less, at most kDenseRounds rounds, in what is left of the budget.
  Nearest from = std::move(first);
  for (int round = 1; round <= kDenseRounds && !budget.over() && from.ratio > 1 &&
                      from.ratio < HUGE_VAL && !from.t.fu.empty();
       ++round) {
    st = prepare(fr, o, false);
    if (!st) break;
    const std::vector<double> miss = miss_ratios(fr, st->spec, from.t, from.nu, from.nv);
    st->f.u = from.t.fu;
    st->f.v = from.t.fv;
    stretch_where_missed(miss, from.nu - o.degree_u, st->f.u);
    stretch_where_missed(miss, from.nv - o.degree_v, st->f.v);
    Nearest next;
    g = search(fr, points, std::move(st),
               " (u and v stretched where the nearest pair missed T, " + std::to_string(round) +
                   (round == 1 ? " round)" : " rounds)"),
               0, true, note, budget, next);
    if (g) return g;
    if (round == 1) why += "; with u and v stretched where the nearest pair missed T";
    why += (round == 1 ? ": " : "; round " + std::to_string(round) + ": ") + note;
    if (!(next.ratio < from.ratio)) break;
    from = std::move(next);
  }
  return g;
}

namespace {

std::optional<GeometricFit> search(const Frame& fr, long points, std::optional<Setup> st,
                                   const std::string& label, double plane, bool calmer,
                                   std::string& why, Budget& budget, Nearest& nearest_out) {
  nearest_out.ratio = -1;
  if (!st) {
    why = "no base surface for the geometric rule";
    return std::nullopt;
  }
  const ScatteredSpec& spec = st->spec;
  const Fractions* f = &st->f;
  const std::optional<Point>& normal = st->normal;
  const ScatteredProblem sp(fr.centred, spec, f->u, f->v);
  // The ratio nu / nv: the data's resolution along and across (its longest row's points over
  // its rows), then square.
  std::size_t longest = 0;
  for (std::size_t j = 0; j < fr.centred.size(); ++j)
    longest = std::max(longest, fr.centred[j].size());
  const double a0 = std::clamp(static_cast<double>(longest) / fr.centred.size(), 1.0 / 16, 16.0);
  // Then one control point across per row (the aspect 0 below): where each row has its own
  // noise or wobble (hand-drawn sections) the net must follow every row on its own, and the
  // rest of the product goes along the rows.
  const int rows = static_cast<int>(fr.centred.size());
  std::vector<double> aspects{a0};
  if (std::abs(a0 - 1) > 0.25) aspects.push_back(1.0);
  if (rows >= sp.min_v()) aspects.push_back(0.0);
  // A bound that cuts off pairs that cannot hold better: more than two control points across
  // per row are decided by the smoothness alone (two rows with 109 across took 3 s a pair).
  const int most_v = std::max(sp.min_v(), 2 * rows);
  const long least = static_cast<long>(sp.min_u()) * sp.min_v();
  auto pair_of = [&](long product, double a) {
    if (a == 0) {
      const int nu = std::max(sp.min_u(), static_cast<int>(product / rows));
      return std::pair{nu, rows};
    }
    int nu = std::max(sp.min_u(), static_cast<int>(std::lround(std::sqrt(product * a))));
    int nv = std::min(most_v, std::max(sp.min_v(), static_cast<int>(product / nu)));
    if (nv == most_v) nu = std::max(sp.min_u(), static_cast<int>(product / nv));
    if (static_cast<long>(nu) * nv > product)
      nu = std::max(sp.min_u(), static_cast<int>(product / nv));
    return std::pair{nu, nv};
  };
  long tried = 0;
  bool guard_failed = false;                  // a pair held T at every point but failed a guard
  std::set<std::pair<int, int>> failed;       // pairs tried that did not hold
  std::map<std::pair<int, int>, Tried> held;  // and those that held
  double nearest = HUGE_VAL;                  // the least worst |S - D| / T of a failed pair
  std::pair<int, int> nearest_pair{0, 0};
  auto missed = [&](int nu, int nv, const Tried& t) {
    failed.insert({nu, nv});
    if (t.ratio < nearest) {
      nearest = t.ratio;
      nearest_pair = {nu, nv};
      nearest_out.t = t;
    }
  };
  // The surface at a product: the first ratio whose pair holds.
  auto at = [&](long product) -> std::optional<std::pair<std::pair<int, int>, Tried>> {
    for (double a : aspects) {
      const auto [nu, nv] = pair_of(product, a);
      if (static_cast<long>(nu) * nv >= points || sp.cost(nu, nv) > kBelowPointsCost) continue;
      if (failed.count({nu, nv})) continue;  // tried before, and it failed
      if (auto h = held.find({nu, nv}); h != held.end()) return std::pair{h->first, h->second};
      if (budget.over()) return std::nullopt;  // not tried: the budget ended
      Tried t = attempt(fr, spec, f->u, f->v, nu, nv, normal, budget, plane, calmer);
      ++tried;
      if (FitMonitor* m = current_monitor()) m->pair_tried(nu, nv, t.holds);
      if (t.holds) {
        held.emplace(std::pair{nu, nv}, t);
        return std::pair{std::pair{nu, nv}, std::move(t)};
      }
      missed(nu, nv, t);
      guard_failed = guard_failed || t.ratio <= 1;
    }
    return std::nullopt;
  };
  // The largest affordable product below the points.
  long hi = points - 1;
  while (hi > least) {
    const auto [nu, nv] = pair_of(hi, a0);
    if (sp.cost(nu, nv) <= kBelowPointsCost) break;
    hi = static_cast<long>(0.8 * static_cast<double>(hi));
  }
  if (hi <= least) {
    why = "no pair below the points is affordable";
    return std::nullopt;
  }
  const long top = hi;
  auto best = at(hi);
  for (int k = 1; k < kTopTries && !best && guard_failed && !budget.over(); ++k) {
    hi = static_cast<long>(0.8 * static_cast<double>(hi));
    if (hi <= least) break;
    best = at(hi);
  }
  // Where nothing held there (T missed, a guard failed or the net folded), a ladder that
  // assumes no ratio and no easiest product: nu halved from the most below the points down to
  // the least, for each nu the nv halved from the most below the points down to the least,
  // these pairs tried largest product first until one holds or the budget ends. A larger pair
  // is not easier where many of its spans have no data: on 60 rows of 2 points across a wave,
  // 11 x 10 and 9 x 9 miss T where 8 x 8 holds (the calm and smoothness terms decide the
  // empty spans, and more of them pull the few points' spans off), so the pairs that hold are
  // not the products above some threshold, and no one ratio finds them on every such input.
  long ladder = 0;  // the ladder's pairs tried
  // (A pair that made no surface, a singular one, says nothing about its neighbours.)
  const bool far = nearest > kLadderReach && nearest < HUGE_VAL;
  if (!best && !budget.over() && !far) {
    std::vector<std::pair<int, int>> rungs;
    for (int nu = static_cast<int>((points - 1) / sp.min_v());; nu /= 2) {
      nu = std::max(nu, sp.min_u());
      for (int nv = static_cast<int>(std::min<long>(most_v, (points - 1) / nu));; nv /= 2) {
        nv = std::max(nv, sp.min_v());
        rungs.emplace_back(nu, nv);
        if (nv == sp.min_v()) break;
      }
      if (nu == sp.min_u()) break;
    }
    std::stable_sort(rungs.begin(), rungs.end(), [](const auto& a, const auto& b) {
      return static_cast<long>(a.first) * a.second > static_cast<long>(b.first) * b.second;
    });
    for (const auto& [nu, nv] : rungs) {
      if (budget.over()) break;
      if (static_cast<long>(nu) * nv >= points || sp.cost(nu, nv) > kBelowPointsCost ||
          failed.count({nu, nv}))
        continue;
      Tried t = attempt(fr, spec, f->u, f->v, nu, nv, normal, budget, plane, calmer);
      ++tried;
      ++ladder;
      if (FitMonitor* m = current_monitor()) m->pair_tried(nu, nv, t.holds);
      if (t.holds) {
        held.emplace(std::pair{nu, nv}, t);
        best = std::pair{std::pair{nu, nv}, std::move(t)};
        hi = static_cast<long>(nu) * nv;
        break;
      }
      missed(nu, nv, t);
    }
  }
  auto budget_note = [&] {
    char limit[32];
    std::snprintf(limit, sizeof limit, "%.2g", budget.limit);
    return "the fallback's work budget (" + std::string(limit) + " flops) ended after " +
           std::to_string(tried) + (tried == 1 ? " pair" : " pairs");
  };
  if (!best) {
    why = "no surface below the points held T with the calm term (" + std::to_string(tried) +
          (tried == 1 ? " pair" : " pairs") + " tried up to " + std::to_string(top) +
          " control points" + (top < points - 1 ? ", the largest affordable" : "") +
          (ladder > 0 ? ", " + std::to_string(ladder) + " of them on a ladder of halved counts" +
                            (budget.over() ? ""
                                           : " down to " + std::to_string(sp.min_u()) + " x " +
                                                 std::to_string(sp.min_v()))
                      : std::string()) +
          (budget.over() ? "; " + budget_note() : std::string()) + ")";
    if (far && !budget.over())
      why +=
          "; no ladder of smaller pairs: they are tried where the nearest misses T by at "
          "most " +
          std::to_string(static_cast<int>(kLadderReach)) + "x";
    if (nearest <= 1) why += "; some held T at the points but left the data's box or folded";
    nearest_out.ratio = nearest;
    nearest_out.nu = nearest_pair.first;
    nearest_out.nv = nearest_pair.second;
    if (nearest > 1 && nearest < HUGE_VAL) {
      char miss[32];
      std::snprintf(miss, sizeof miss, "%.3g", nearest);
      why += "; the nearest, " + std::to_string(nearest_pair.first) + " x " +
             std::to_string(nearest_pair.second) + ", missed T by " + miss + "x";
    }
    return std::nullopt;
  }
  long lo = least - 1;
  bool cut = false;  // the budget ended before the bisection or the descent did
  for (int k = 0; k < kBisections && hi - lo > 1; ++k) {
    if (budget.over()) {
      cut = true;
      break;
    }
    const long mid = lo + (hi - lo) / 2;
    if (auto m = at(mid)) {
      hi = mid;
      best = std::move(m);
    } else {
      lo = mid;
    }
  }
  // Then one fewer along u or along v while either holds (the bisection's pairs keep the
  // ratio; this makes the pair minimal under the same criterion: solve, guard and fold), for
  // at most kDescentTries new pairs: where that budget ends first the pair is not called
  // minimal (two long rows with an outlier took 95 such steps, 23 s).
  bool minimal = false;
  long descent = 0;
  for (bool moved = true; moved;) {
    moved = false;
    if (descent >= kDescentTries || cut) break;
    const auto [nu, nv] = best->first;
    for (const auto& [a, b] : {std::pair{nu - 1, nv}, std::pair{nu, nv - 1}}) {
      if (a < sp.min_u() || b < sp.min_v() || failed.count({a, b})) continue;
      auto h = held.find({a, b});
      if (h == held.end() && (descent >= kDescentTries || budget.over())) {
        moved = true;  // not known: the budget ended before the pair was shown minimal
        cut = cut || budget.over();
        break;
      }
      Tried t = h != held.end()
                    ? h->second
                    : attempt(fr, spec, f->u, f->v, a, b, normal, budget, plane, calmer);
      if (h == held.end()) {
        ++tried;
        ++descent;
        if (FitMonitor* m = current_monitor()) m->pair_tried(a, b, t.holds);
        if (t.holds) held.emplace(std::pair{a, b}, t);
      }
      if (!t.holds) failed.insert({a, b});
      if (t.holds) {
        best = std::pair{std::pair{a, b}, std::move(t)};
        moved = true;
        break;
      }
    }
    if (!moved) minimal = true;
  }
  const auto [nu, nv] = best->first;
  GeometricFit g;
  g.surface = std::move(best->second.s);
  const ScatteredProblem won(fr.centred, spec, std::move(best->second.fu),
                             std::move(best->second.fv));
  g.u = won.u_at(nu);
  g.v = won.v_at(nv);
  g.corrections = best->second.corrections;
  g.smoothing = best->second.smoothing;
  g.tried = tried;
  const std::vector<char> cells = covered_spans(g.surface, g.u, g.v);
  const long covered = std::count(cells.begin(), cells.end(), 1);
  g.stop =
      std::string(minimal ? "minimal below the points" : "below the points") +
      ": the geometric rule" + label +
      " with a calm net where the data is not "
      "(data in " +
      std::to_string(covered) + " of the " + std::to_string(cells.size()) +
      " knot spans), nu x nv by " +
      (ladder > 0 ? "a ladder of halved counts (" + std::to_string(ladder) +
                        (ladder == 1 ? " pair), then " : " pairs), then ")
                  : std::string()) +
      "bisection on the product, then one fewer along u or v while it held" +
      (minimal || cut ? std::string() : " (stopped after " + std::to_string(kDescentTries) + ")") +
      (cut ? " (stopped: " + budget_note() + ")" : std::string()) + " (" + std::to_string(tried) +
      " pairs)";
  return g;
}

}  // namespace

}  // namespace sfit::detail
