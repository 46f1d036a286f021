// The fit driver (fit_driver.h): the stages every method runs in, once each.
#include "fit_driver.h"

#include <optional>

#include "adaptive_knots.h"
#include "aligned_fit.h"
#include "corner_knots.h"
#include "final_check.h"
#include "fit_frame.h"
#include "fit_registry.h"
#include "parallel.h"
#include "sfit/error.h"

namespace sfit::detail {

Centring centre_rows(const Rows& rows, int threads_option) {
  Centring c;
  c.threads = threads_for(rows, threads_option);
  c.box = box_of(rows, c.threads);
  c.centre = 0.5 * (c.box.min + c.box.max);
  c.roundoff = kRoundoffRelative * c.box.diagonal();
  c.centred = rows;
  parallel_for(rows.size(), c.threads, [&](std::size_t j) {
    for (Point& p : c.centred.mutable_row(j)) p -= c.centre;
  });
  return c;
}

namespace {

FitResult run(const Rows& rows, const FitOptions& o, bool adapt, MethodState* state,
              const std::vector<std::size_t>* changed) {
  // 1. Validate once: rows and options; errors name the original rows and points.
  validate(rows, o);
  const MethodEntry method = method_entry(o.method);
  // 2. Seams and orientation (seam_alignment.h, docs/seams.md), for every method: the method
  // runs on the re-ordered rows; u, the worst point and the report refer to the original
  // points after restore_original_order().
  std::optional<RowAlignment> alignment;
  if (o.seam != SeamMode::kKeep || o.orient != OrientMode::kKeep) {
    RowAlignment a = alignment_for(rows, o);
    if (!a.identity()) alignment = std::move(a);
  }
  std::optional<Rows> aligned;
  std::vector<double> offsets;
  if (alignment) {
    aligned = apply_alignment(rows, *alignment);
    offsets = seam_offsets(*alignment, o.closed_u);
  }
  const Rows& work = aligned ? *aligned : rows;
  FitOptions mo = o;  // the rows are aligned now
  mo.seam = SeamMode::kKeep;
  mo.orient = OrientMode::kKeep;
  // 3. Centre once (the box of the aligned rows is the original rows' box).
  const Centring centring = centre_rows(work, o.threads);
  // 4. The method (as IncrementalFit's state where one is given).
  const FitSpec spec{work, mo, offsets, centring};
  FitResult r;
  if (!state) {
    r = method.fit(spec);
  } else if (alignment || !changed) {
    r = state->fit(spec);
    if (alignment) state->forget();  // its rows were re-ordered: the next edit refits in full
  } else {
    r = state->update(spec, *changed);
  }
  // 5. Corner knots (corner_knots.h) beside the method's surface, on the rows it fitted;
  // kept only where smaller and, below, where the final check confirms it.
  std::optional<FitResult> plain;
  if (adapt && !state && corner_knots_apply(mo)) {
    FitResult c = r;
    if (corner_knots(work, mo, centring.threads, c)) {
      plain = std::move(r);
      r = std::move(c);
    }
  }
  if (alignment) {
    restore_original_order(r, rows, *alignment);
    if (plain) restore_original_order(*plain, rows, *alignment);
  }
  // 6. One final check, one criterion: the surface as returned and written, at every point;
  // the corner surface where it holds there, else the method's.
  bool checked = false;
  if (plain) {
    try {
      check_as_written(r, rows, o);
      checked = r.report.within_tolerance;
    } catch (const Error&) {
    }
    if (!checked) r = std::move(*plain);
  }
  if (!checked) check_as_written(r, rows, o);
  // 7. Knots where the shape needs them (kept only where smaller), and where kept the same
  // final check on the surface that is returned.
  if (adapt && o.knots == KnotRule::kAdaptive && adapt_knots(rows, o, r))
    check_as_written(r, rows, o);
  return r;
}

}  // namespace

FitResult run_fit(const Rows& rows, const FitOptions& o, bool adapt) {
  return run(rows, o, adapt, nullptr, nullptr);
}

FitResult run_fit(const Rows& rows, const FitOptions& o, MethodState& state,
                  const std::vector<std::size_t>* changed) {
  return run(rows, o, false, &state, changed);
}

}  // namespace sfit::detail
