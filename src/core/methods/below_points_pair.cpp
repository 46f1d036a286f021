// One pair of the fallback below the points, solved and judged (below_points_pair.h).
#include "below_points_pair.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "geometric_params.h"
#include "sfit/fold_check.h"

namespace sfit::detail {

namespace {

// The parameters are corrected where the worst point misses T by at most this factor.
constexpr double kCorrectReach = 3;
// attempt()'s `calmer` weights: the smoothness raised 10, 100 and 1000 times, each corrected
// (up to kCorrectionRounds) where it is calm and unfolded and misses T by at most this factor.
constexpr double kCalmerReach = 2;
constexpr double kCalmerMost = 1e3;
// The work of one solve at (nu, nv) over `points` points (Budget).
double solve_work(const ScatteredProblem& sp, int nu, int nv, bool calmed, std::size_t points) {
  return (calmed ? 2 : 1) * sp.cost(nu, nv) + kPointWork * static_cast<double>(points);
}

// The data term of one problem at (nu, nv), summed on first use and kept for every weight
// solved on it: ScatteredProblem::solve() sums it again for each (the same values, so the
// same bits), and a pair's weights, lowered and in between, are solved on one problem (on
// table1_synthetic at 1e-4 the sums were 6 % of the fit, half of them repeated).
struct DataTerm {
  const ScatteredProblem* sp = nullptr;
  int nu = 0, nv = 0;
  std::vector<double> band;
  std::vector<Point> rhs;
  bool summed = false;
  DataTerm(const ScatteredProblem& p, int u, int v) : sp(&p), nu(u), nv(v) {}
  bool ready() {
    if (nu < sp->min_u() || nv < sp->min_v()) return false;
    if (!summed) sp->assemble(nu, nv, band, rhs);
    summed = true;
    return true;
  }
  // ScatteredProblem::solve() on the kept sums.
  bool solve(double w, Surface& s, double calm, const Point* normal) {
    return ready() && scattered_solve(sp->spec(), nu, nv, band, rhs, w, s, calm, normal);
  }
};

// The calm solve (ScatteredProblem::solve() with the calm term on the height along `normal`),
// the plane's coordinates at smoothness at least `plane` where > 0.
bool calm_solve(DataTerm& d, double w, Surface& s, const std::optional<Point>& normal,
                double plane) {
  if (!(plane > 0) || !normal)
    return d.solve(w, s, normal ? kCalm : 0.0, normal ? &*normal : nullptr);
  Surface flat;
  if (!d.ready() || !scattered_solve(d.sp->spec(), d.nu, d.nv, d.band, d.rhs, w, s, kCalm) ||
      !scattered_solve(d.sp->spec(), d.nu, d.nv, d.band, d.rhs, std::max(w, plane), flat))
    return false;
  const Point& n = *normal;
  for (std::size_t I = 0; I < s.control.size(); ++I)
    s.control[I] = flat.control[I] + (s.control[I] - flat.control[I]).dot(n) * n;
  return true;
}

// One solve at the problem's fractions: the smoothness as the geometric search's, and lowered
// where T was missed; every point judged (the exact worst ratio). `holds`: T at every point.
// `d`: the problem's data term at (nu, nv).
Tried solve_once(const ScatteredProblem& sp, DataTerm& d, const Frame& fr, int nu, int nv,
                 const std::optional<Point>& normal, Budget& budget, double plane) {
  Tried best;
  const std::vector<double> u = sp.u_at(nu), v = sp.v_at(nv);
  const double work = solve_work(sp, nu, nv, normal.has_value(), fr.centred.total_points());
  for (double w = kSmoothing; w >= kSmoothing * kSmoothingLower; w *= kSmoothingLower) {
    Surface s;
    budget.spent += work;
    if (!calm_solve(d, w, s, normal, plane)) break;
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
              Budget& budget, double plane, bool calmer) {
  Tried best;
  const double pass = kPointWork * static_cast<double>(fr.centred.total_points());
  std::vector<double> fu = fu0, fv = fv0;
  // The best round's data term (its problem's fractions are best.fu, best.fv).
  std::vector<double> best_band;
  std::vector<Point> best_rhs;
  bool best_summed = false;
  for (int round = 0; round <= kCorrectionRounds; ++round) {
    const ScatteredProblem sp(fr.centred, spec, std::move(fu), std::move(fv));
    DataTerm d(sp, nu, nv);
    Tried t = solve_once(sp, d, fr, nu, nv, normal, budget, plane);
    if (!(t.ratio < best.ratio)) break;
    t.fu = sp.fractions_u();
    t.fv = sp.fractions_v();
    t.corrections = round;
    best = std::move(t);
    best_band = std::move(d.band);
    best_rhs = std::move(d.rhs);
    best_summed = d.summed;
    // A far miss is not corrected (no round was seen to bring it within T; each costs a solve).
    if (best.holds || round == kCorrectionRounds || best.ratio > kCorrectReach) break;
    std::vector<double> u = sp.u_at(nu), v = sp.v_at(nv);
    budget.spent += pass;
    project_parameters(best.s, fr.centred, u, v, kNewtonSteps, fr.threads);
    to_fractions(best.s, u, v, fu, fv);
  }
  if (best.holds) {
    const ScatteredProblem sp(fr.centred, spec, best.fu, best.fv);
    DataTerm d(sp, nu, nv);  // the same fractions as the best round's: its sums
    d.band = std::move(best_band);
    d.rhs = std::move(best_rhs);
    d.summed = best_summed;
    const std::vector<double> u = sp.u_at(nu), v = sp.v_at(nv);
    // The rule's guard and no fold, at the parameters the surface was solved at.
    auto guarded = [&](const Surface& s, const std::vector<double>& su,
                       const std::vector<double>& sv) {
      return stays_near_where_covered(s, su, sv, fr.centred_box) &&
             geometric_fold(s) <= kFoldRelative * fr.box.diagonal();
    };
    best.holds = guarded(best.s, u, v);
    const double work = solve_work(sp, nu, nv, normal.has_value(), fr.centred.total_points());
    // The surface `s` solved on `sp` at weight `w` into `best` where it holds T and the guards;
    // where it is calm and unfolded but misses T by at most `reach`, the parameters corrected
    // on it and the pair solved again at `w`, at most `rounds` times (each round first asks
    // the budget where `budgeted`).
    auto settle = [&](Surface s, double w, int rounds, double reach, bool budgeted) {
      std::vector<double> cu = u, cv = v, gu, gv;
      PairVerdict verdict = fr.judge(s, cu, cv, nullptr, nullptr, false);
      for (int round = 0; guarded(s, cu, cv); ++round) {
        if (verdict.holds) {
          best.s = std::move(s);
          best.ratio = verdict.ratio;
          best.smoothing = w;
          best.holds = true;
          if (round > 0) {
            best.fu = std::move(gu);
            best.fv = std::move(gv);
            best.corrections += round;
          }
          return;
        }
        if (round == rounds || verdict.ratio > reach || (budgeted && budget.over())) return;
        budget.spent += pass + work;
        project_parameters(s, fr.centred, cu, cv, kNewtonSteps, fr.threads);
        to_fractions(s, cu, cv, gu, gv);
        const ScatteredProblem again(fr.centred, spec, gu, gv);
        DataTerm da(again, nu, nv);
        if (!calm_solve(da, w, s, normal, plane)) return;
        cu = again.u_at(nu);
        cv = again.v_at(nv);
        verdict = fr.judge(s, cu, cv, nullptr, nullptr, false);
      }
    };
    // Where the smoothness was lowered to hold T and a guard failed (a span with few points
    // swung out of the box, or the net folded): the weights in between, calmer first, each
    // corrected once where it missed T narrowly.
    for (double w = kSmoothing * 0.1; !best.holds && w > 1.5 * best.smoothing; w *= 0.1) {
      Surface s;
      budget.spent += work;
      if (!calm_solve(d, w, s, normal, plane)) break;
      settle(std::move(s), w, 1, kSmoothingReach, false);
    }
    // The stretched pass (calmer): where T held but a guard failed, calmer weights than the
    // search's, each corrected by projection (at that weight) while it stays calm and unfolded.
    for (double w = kSmoothing * 10; calmer && !best.holds && w <= kSmoothing * kCalmerMost;
         w *= 10) {
      Surface s;
      budget.spent += work;
      if (!calm_solve(d, w, s, normal, plane)) break;
      settle(std::move(s), w, kCorrectionRounds, kCalmerReach, true);
    }
    // Where the height alone was calmed and a guard failed: the calm term on every axis.
    if (!best.holds && normal) {
      Surface s;
      budget.spent += work;
      if (d.solve(best.smoothing, s, kCalm, nullptr)) {
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

std::optional<Setup> prepare(const Frame& fr, const FitOptions& o, bool warp) {
  std::optional<Fractions> f = base_surface_fractions(fr.centred, o.closed_u, o.closed_v);
  if (!f) return std::nullopt;
  if (warp) warp_by_chord(fr.centred, f->u);
  Setup st{std::move(*f), {o.degree_u, o.degree_v, o.closed_u, o.closed_v, fr.threads}, {}};
  // An open sheet's height direction: the normal of the points' best plane (the calm term
  // acts on the height only). Closed rows have none: their net is continued linearly.
  if (!o.closed_u && !o.closed_v) {
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    Point mean = Point::Zero();
    for (const Point& p : fr.centred.points()) mean += p;
    mean /= static_cast<double>(fr.centred.total_points());
    for (const Point& p : fr.centred.points()) cov += (p - mean) * (p - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    if (eig.info() == Eigen::Success) st.normal = eig.eigenvectors().col(0).normalized();
  }
  return st;
}

void warp_by_chord(const Rows& rows, std::vector<double>& fu) {
  const auto& off = rows.offsets();
  std::vector<double> c;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const auto r = rows[j];
    const std::size_t m = r.size(), o = off[j];
    if (m < 2) continue;
    c.assign(m, 0.0);
    for (std::size_t k = 1; k < m; ++k) c[k] = c[k - 1] + (r[k] - r[k - 1]).norm();
    if (!(c[m - 1] > 0)) continue;
    const double a = fu[o], b = fu[o + m - 1];
    for (std::size_t k = 0; k < m; ++k)
      fu[o + k] = std::clamp(0.5 * fu[o + k] + 0.5 * (a + c[k] / c[m - 1] * (b - a)), 0.0, 1.0);
  }
}

}  // namespace sfit::detail
