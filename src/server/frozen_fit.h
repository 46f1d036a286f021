// The quick refit of a drag (docs/editor.md, "How a drag is refitted"): least squares at the
// counts, knots and parameters of the full fit the drag started from, all FROZEN for the drag.
// Whatever made that fit (the surface search, the two stages, any parameter rule, adaptive
// knots), the refit is then a linear map of the data: the normal equations' matrix depends on
// the parameters and knots only, so it is factorised once (when a point is selected or the drag
// starts) and every drag step costs one right-hand side and two triangular solves. Moving point
// k by d moves the control points by g_k d, g_k = N^-1 B_k^T: the page's prediction
// (influence.h). The full fit at rest recomputes counts, knots and parameters.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::server {

class FrozenFit {
 public:
  /// The frozen problem of `at`, the full fit of `rows`; nullptr with `why` where it cannot be
  /// made: weighted rows, parameters that do not reproduce the fit's own check (rows the fit
  /// reordered: seams aligned, rows reversed), more control points than kMaxUnknowns, or a
  /// factorisation that failed.
  static std::shared_ptr<const FrozenFit> make(const Rows& rows, const FitResult& at,
                                               std::string& why);
  /// Control points above which the frozen refit is not made (a sparse factorisation grows
  /// faster than the unknowns: 0.6-1.6 s at 94 x 96 on a loaded 2-core machine, and the
  /// session waits for it): the drag then refits as before (IncrementalFit).
  static constexpr std::size_t kMaxUnknowns = 12000;
  ~FrozenFit();

  /// The least-squares surface of `rows` (the drag's rows: the same sizes as at the start) at
  /// the frozen counts, knots and parameters, every point checked against T per axis: the
  /// report says within T or not ("quick refit"), stop_reason "frozen for the drag".
  FitResult refit(const Rows& rows) const;
  /// g_k of point `index` of row `row`: the control points' motion per unit motion of the
  /// point, one number per distinct control point (Surface::control's order).
  std::vector<double> influence(std::size_t row, std::size_t index) const;
  /// Seconds spent building (assembly and factorisation).
  double seconds() const { return seconds_; }

 private:
  struct Impl;
  explicit FrozenFit(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  double seconds_ = 0;
};

}  // namespace sfit::server
