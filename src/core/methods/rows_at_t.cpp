// The two stages with the rows at all of T (rows_at_t.h).
#include "rows_at_t.h"

#include <algorithm>

#include "fit_monitor.h"
#include "fit_registry.h"
#include "sfit/error.h"
#include "sfit/fold_check.h"

namespace sfit::detail {

std::optional<FitResult> fit_rows_at_t(const FitSpec& spec, const FitOptions& two_stage,
                                       const FitOptions& search, const FitResult& halves,
                                       const CountFloor& floor_at_t) {
  const Centring& c = spec.centring;
  const long now_best = static_cast<long>(halves.surface.count_u) * halves.surface.count_v;
  // Noise near T leaves a few per cent at twice the time: the run is made only where the
  // estimate leaves a tenth.
  FitOptions half = search;
  half.tolerance *= 0.5;
  const int at_half = count_floor(c.centred, half, two_stage.parametrization, c.roundoff).nu;
  const double estimate = static_cast<double>(halves.surface.count_u) * floor_at_t.nu /
                          std::max(at_half, 1) * static_cast<double>(spec.rows.size());
  if (10 * estimate >= 9 * static_cast<double>(now_best)) return std::nullopt;
  progress_phase("rows take T", 1);
  std::optional<FitResult> out;
  try {
    // The two-stage method, asked of the registry by name (no method calls another directly).
    FitResult a = method_entry("sfit01").fit(
        FitSpec{spec.rows, two_stage, spec.seam_offsets, c, /*rows_take_all=*/true});
    const long n = static_cast<long>(a.surface.count_u) * a.surface.count_v;
    const bool folds = a.report.fold > kFoldRelative * c.box.diagonal();
    if (a.report.within_tolerance && n < now_best && !(search.fold_guard && folds))
      out = std::move(a);
  } catch (const Error& e) {  // a re-representation that cannot hold T: none
    if (e.code() != ErrorCode::kToleranceNotMet) throw;
  }
  progress_advance(1);
  return out;
}

}  // namespace sfit::detail
