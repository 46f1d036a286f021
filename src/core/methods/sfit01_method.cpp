// The paper's two-stage method (FitMethod::kSfit01, docs/method.md): its driver. An attempt
// (sfit01_attempt.h: curve stage on the rows, re-representation on a common count, transverse
// stage on the columns of control points) at the stage budget T/2, tightened until the final
// check holds; the rule's fallbacks, the fold guard and update_aligned() after edits of some rows.
// Unchanged in its results by the split into frame and methods (the tests compare bits).
#include <algorithm>
#include <optional>

#include "aligned_fit.h"
#include "deviation.h"
#include "final_check.h"
#include "fit_driver.h"
#include "fit_frame.h"
#include "fit_monitor.h"
#include "fit_registry.h"
#include "sfit/error.h"
#include "sfit/fold_check.h"
#include "sfit01_attempt.h"
#include "surface_fitter.h"

namespace sfit::detail {

FitResult SurfaceFitter::finish(Attempt& at, int tightenings, const DeviationCheck& check,
                                double seconds_start) const {
  // Shape measures (fold_check.h) on the centred surface and rows: the surface
  // moved to the data's coordinates and back, as the surface returned is (the same bits).
  const BoundingBox box{box_.min - centre_, box_.max - centre_};
  Surface round_trip = at.surface;
  for (Point& p : round_trip.control) p += centre_;
  for (Point& p : round_trip.control) p -= centre_;
  const ShapeMeasures m = measure_shape(round_trip, centred(), at.u, at.v, box, o_.closed_u);
  FitResult out = frame_result(std::move(at.surface), std::move(at.u), std::move(at.v),
                               std::move(at.report), check, m, centred(), centre_, roundoff_, o_);
  FitReport& r = out.report;
  r.parametrization = rule_;
  r.parametrization_across = across_.value_or(rule_);
  r.tightenings = tightenings;
  r.seconds = now() - seconds_start;
  return out;
}

namespace {
long size_of(const FitResult& f) {
  return static_cast<long>(f.surface.count_u) * f.surface.count_v;
}
}  // namespace

FitResult fit_sfit01_method(const FitSpec& spec) {
  SurfaceFitter f(spec.options);
  f.rows_take_all(spec.rows_take_all);
  f.keep_state(false);  // one fit, no update
  return f.fit_aligned(spec.rows, spec.seam_offsets, &spec.centring);
}

namespace {

// IncrementalFit's state (MethodState, fit_registry.h): a SurfaceFitter that keeps its row
// stage between the driver's fits. It must be this class, not the registry's function: the
// update reuses the curve stage's per-row fits and re-representations (docs/method.md 7.7),
// which only the two-stage method has.
class Sfit01State final : public MethodState {
 public:
  explicit Sfit01State(const FitOptions& o) : f_(o) {}
  FitResult fit(const FitSpec& spec) override {
    return f_.fit_aligned(spec.rows, spec.seam_offsets, &spec.centring);
  }
  FitResult update(const FitSpec& spec, const std::vector<std::size_t>& changed) override {
    return f_.update_aligned(spec.rows, changed, spec.centring);
  }
  void forget() override { f_.forget(); }
  std::size_t rows_refitted() const override { return f_.rows_refitted(); }

 private:
  SurfaceFitter f_;
};

}  // namespace

std::unique_ptr<MethodState> sfit01_state(const FitOptions& options) {
  return std::make_unique<Sfit01State>(options);
}

FitResult SurfaceFitter::fit_given(const Rows& rows) {
  if (o_.parametrization != Parametrization::kFewest) return fit_rule(rows, o_.parametrization);
  // Every rule in turn; the surface with the fewest control points wins (the first rule on a
  // tie, the paper's first). update_aligned() then refits in full (valid_ is cleared), which is
  // what this does.
  const double t0 = now();
  std::optional<FitResult> best;
  std::vector<Parametrization> rules = {Parametrization::kPaper, Parametrization::kUniform,
                                        Parametrization::kChord, Parametrization::kCentripetal};
  for (Parametrization r : automatic_rules()) rules.push_back(r);  // opted in, after these
  for (Parametrization rule : rules) {
    FitResult r = fit_rule(rows, rule);
    const auto size = [](const FitResult& f) {
      return static_cast<long>(f.surface.count_u) * f.surface.count_v;
    };
    // Within tolerance first, then fold-free, then the fewest control points.
    const auto rank = [&](const FitResult& f) {
      return 2 * !f.report.within_tolerance + (o_.fold_guard && folds(f));
    };
    if (!best || rank(r) < rank(*best) || (rank(r) == rank(*best) && size(r) < size(*best)))
      best = std::move(r);
  }
  valid_ = false;
  best->report.seconds = now() - t0;
  return std::move(*best);
}

FitResult SurfaceFitter::fit_rule(const Rows& rows, Parametrization requested) {
  // The fold guard (fold_check.h, docs/seams.md): a surface that doubles back on
  // itself between rows is refitted with chord-length, then centripetal, positions across the
  // rows (uneven row spacing at the paper's even v is what folds it); the fold-free one with
  // the fewest control points wins. Where none is fold-free, the least folded stays and its
  // report.fold says by how much (the CLI warns).
  const double t0 = now();
  FitResult r = fit_rule_unguarded(rows, requested);
  if (!o_.fold_guard || !folds(r)) return r;
  progress_phase("fold guard", 2);
  const Parametrization used = rule_;
  std::optional<FitResult> best;
  for (Parametrization across : {Parametrization::kChord, Parametrization::kCentripetal}) {
    across_ = across;
    try {
      FitResult c = fit_rule_unguarded(rows, requested);
      if (c.report.within_tolerance && !folds(c) && stays_near_the_data(c.surface, box_) &&
          (!best || size_of(c) < size_of(*best)))
        best = std::move(c);
    } catch (const Error& e) {
      if (e.code() != ErrorCode::kToleranceNotMet) throw;
    }
  }
  across_.reset();
  valid_ = false;  // update_aligned() refits in full
  if (!best && !degree_lowered_) {
    // No rule across the rows avoided the fold: lower degrees across them, one step at a time
    // down to 1. A cubic across unevenly spaced rows overshoots between them (the ragged 3.4 MW
    // blade dips 4.2 cm below its root section at 9 x 9 rows and control points); a quadratic
    // there does not. Where the columns interpolate rows that each cover a different part of
    // the surface (rows cut by a hole, noise beyond T: every column passes through every row),
    // a quadratic still folds and only straight stretches between the rows do not (a noisy
    // range image with a hole, at T a ninth of its noise). The report's degree says so, and
    // the CLI; --no-fold-guard keeps the degree asked for.
    for (int degree = o_.degree_v - 1; degree >= 1; --degree) {
      FitOptions lower = o_;
      lower.degree_v = degree;
      SurfaceFitter f(lower);
      f.degree_lowered_ = true;  // this loop lowers it further (each step is a whole fit)
      f.keep_state_ = false;     // its fit is returned, never updated
      f.row_seam_offsets_ = row_seam_offsets_;
      f.given_ = given_;  // the same rows: the same centring
      try {
        FitResult c = f.fit_rule(rows, requested);
        if (c.report.within_tolerance && !folds(c) && stays_near_the_data(c.surface, box_)) {
          c.report.seconds = now() - t0;
          return c;
        }
      } catch (const Error& e) {
        if (e.code() != ErrorCode::kToleranceNotMet) throw;
      }
    }
  }
  if (!best) {
    rule_ = used;
    r.report.seconds = now() - t0;
    return r;
  }
  rule_ = best->report.parametrization;
  best->report.seconds = now() - t0;
  return std::move(*best);
}

bool SurfaceFitter::folds(const FitResult& r) const {
  return r.report.fold > kFoldRelative * box_.diagonal();
}

FitResult SurfaceFitter::fit_rule_unguarded(const Rows& rows, Parametrization requested) {
  rule_ = requested;
  if (rule_ == Parametrization::kPaper) return fit_with_rule(rows);
  // The geometric rules (docs/method.md 7.4) hold the tolerance on their own where they can; where
  // they cannot (a re-representation or the final check fails: positions whose systems are
  // singular near interpolation, rows whose parameters disagree), or where the surface swings
  // away between the points it holds (the frame's guards, failed_guard()), the paper's rule, which
  // always can, fits instead; the report names the rule used. report.seconds covers all of it: the
  // check below, and a failed attempt before a fallback.
  const double t0 = now();
  try {
    FitResult r = fit_with_rule(rows);
    if (r.report.within_tolerance && !failed_guard(r.surface, box_) &&
        !(o_.fold_guard && folds(r))) {
      r.report.seconds = now() - t0;
      return r;
    }
  } catch (const Error& e) {
    if (e.code() != ErrorCode::kToleranceNotMet) throw;
  }
  rule_ = Parametrization::kPaper;
  FitResult r = fit_with_rule(rows);
  r.report.seconds = now() - t0;
  return r;
}

FitResult SurfaceFitter::fit_with_rule(const Rows& rows) {
  const double t0 = now();
  centre(rows);  // the rows are validated and centred (the driver)
  Attempt at;
  int tightenings = 0;
  DeviationCheck check;
  valid_ = false;
  for (double shrink = 1.0;; shrink *= 0.5) {
    // Stage budget: T/2 with a relative margin so T/2 + T/2 stays <= T after rounding;
    // at T = 0 the round-off allowance.
    // With rows_take_all_ the rows get T less half the allowance, the columns that half
    // (fit_once()).
    Point bound;
    for (int a = 0; a < 3; ++a) {
      const double t = o_.tolerance[a] * (1 - 1e-9) * shrink;
      bound[a] = o_.tolerance[a] > 0
                     ? std::max(rows_take_all_ ? t - 0.5 * roundoff_ : 0.5 * t, 0.5 * roundoff_)
                     : 0.5 * roundoff_;
    }
    at = fit_once(bound, nullptr);
    if (tightenings == 0) {
      bound_ = bound;
      valid_ = true;
    } else {
      valid_ = false;  // the kept state is not the first attempt's
    }
    progress_phase("check", 1);
    check = check_deviation(at.surface, centred(), at.u, at.v, o_.tolerance, roundoff_, threads_);
    progress_advance(1);
    if (check.within || tightenings == 3) break;
    ++tightenings;
  }
  return finish(at, tightenings, check, t0);
}

FitResult SurfaceFitter::update_aligned(const Rows& rows, const std::vector<std::size_t>& changed,
                                        const Centring& c) {
  const double t0 = now();
  const EndOfFit end{*this};
  // The fit in full, as the driver's fit_aligned() of these rows would run it.
  const auto in_full = [&] { return fit_aligned(rows, {}, &c); };
  if (!valid_ || !keep_state_ || rows.size() != centred_rows_ || c.box.min != box_.min ||
      c.box.max != box_.max || rule_ != o_.parametrization)  // (never equal for kFewest)
    return in_full();
  // Same box, so the same centre, round-off allowance and budget: refresh the edited rows.
  std::vector<char> mark(rows.size(), 0);
  for (std::size_t j : changed) mark.at(j) = 1;
  valid_ = false;  // until the update completes
  threads_ = c.threads;
  centred_ = &c.centred;  // the driver's: the rows less the same centre
  Attempt at;
  try {
    at = fit_once(bound_, &mark);
  } catch (const Error& e) {
    if (e.code() != ErrorCode::kToleranceNotMet) throw;
    return in_full();  // the fit would have met the same failure first: do exactly what it does
  }
  const DeviationCheck check =
      check_deviation(at.surface, centred(), at.u, at.v, o_.tolerance, roundoff_, threads_);
  if (!check.within) return in_full();  // the fit would tighten: do exactly that
  FitResult out = finish(at, 0, check, t0);
  if (rule_ != Parametrization::kPaper && failed_guard(out.surface, box_))
    return in_full();  // the fit falls back to the paper's rule: do exactly that
  if (o_.fold_guard && folds(out)) return in_full();  // the fit guards the fold
  valid_ = true;
  return out;
}

}  // namespace sfit::detail
