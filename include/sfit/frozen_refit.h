// The refit at frozen counts, knots and parameters (docs/editor.md, "How a drag is refitted"):
// least squares at the counts, knots and parameters of a finished fit, all FROZEN. Whatever
// made that fit (the surface search, the two stages, any parameter rule, adaptive knots), the
// refit is then a linear map of the data: the normal equations' matrix depends on the
// parameters and knots only, so it is factorised once (make()) and every refit costs one
// right-hand side and two triangular solves. Moving point k by d moves the control points by
// g_k d, g_k = N^-1 B_k^T (influence()). A full fit recomputes counts, knots and parameters.
// The editor's drag refits through it; an application can do the same.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit {

class FrozenRefit {
 public:
  /// The frozen problem of `at`, the fit of `rows`; nullptr with `why` where it cannot be
  /// made: weighted rows, parameters that do not reproduce the fit's own check (rows the fit
  /// reordered: seams aligned, rows reversed), more control points than kMaxUnknowns, rows
  /// other than a grid on a surface closed both ways, or a factorisation that failed (a knot span
  /// without data is decided by a small smoothness term, so it does not fail for that).
  static std::shared_ptr<const FrozenRefit> make(const Rows& rows, const FitResult& at,
                                                 std::string& why);
  /// Control points above which make() refuses (the general path's banded factorisation
  /// grows as unknowns x band^2: 0.13-0.22 s at 92-98 x 100 on a loaded 2-core machine).
  static constexpr std::size_t kMaxUnknowns = 12000;
  ~FrozenRefit();
  FrozenRefit(const FrozenRefit&) = delete;
  FrozenRefit& operator=(const FrozenRefit&) = delete;

  /// The least-squares surface of `rows` (as many rows as make()'s, each of the same length)
  /// at the frozen counts, knots and parameters, every point checked against T per axis by
  /// check_fit_as_written() (sfit/fit_check.h): the report says within T or not, stop_reason
  /// "quick refit: ..."; the shape measures (fold, excursion) are those of the fit at make().
  /// Throws Error(kUsage) for rows of other sizes.
  FitResult refit(const Rows& rows) const;
  /// g_k of point `index` of row `row`: the control points' motion per unit motion of the
  /// point, one number per distinct control point (Surface::control's order). Throws
  /// Error(kUsage) for a point outside the rows.
  std::vector<double> influence(std::size_t row, std::size_t index) const;
  /// Seconds make() spent (assembly and factorisation).
  double seconds() const { return seconds_; }

 private:
  struct Impl;
  explicit FrozenRefit(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  double seconds_ = 0;
};

}  // namespace sfit
