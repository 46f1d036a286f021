// The one fit driver above the methods (docs/method.md, "How a fit runs"): validate once,
// seam alignment once, centre once, the method chosen from the registry (fit_registry.h),
// one final check with one criterion (check_as_written(), final_check.h) for every method,
// then the optional knot adaptation. fit_surface() is this. Private.
#pragma once

#include <span>
#include <vector>

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

/// The rows centred on their box, made once per fit (the same values the two-stage method and
/// the surface search computed each for itself before).
struct Centring {
  int threads = 1;  ///< threads_for() the rows
  BoundingBox box;  ///< the data's box, in the data's coordinates
  Point centre = Point::Zero();
  double roundoff = 0;  ///< kRoundoffRelative x the box's diagonal
  Rows centred;         ///< the rows less `centre`
};
/// The centring of `rows` at the thread count `threads_option` asks for (FitOptions::threads).
Centring centre_rows(const Rows& rows, int threads_option);

/// What a method gets: validated rows, aligned already (seams and orientation), and their
/// centring. A method returns its candidate surface in the data's coordinates (the centre
/// added back), with u, v of the aligned rows' points and its report; it neither validates
/// nor runs the final check.
struct FitSpec {
  const Rows& rows;                      ///< validated, aligned, in the data's coordinates
  const FitOptions& options;             ///< seam and orient kKeep (the rows are aligned)
  std::span<const double> seam_offsets;  ///< fractional seams of the aligned rows; empty: none
  const Centring& centring;              ///< of `rows`
  /// A two-stage method's budgets: false (the paper's) T/2 for the rows and T/2 for the
  /// columns; true all of T for the rows, the columns interpolating their control points
  /// (rows_at_t.h). Other methods ignore it.
  bool rows_take_all = false;
};

/// fit_surface() (progress and cancel set up by the caller): validate, align, centre, the
/// registered method options.method, the final check; knots adaptive when `adapt_knots`.
FitResult run_fit(const Rows& rows, const FitOptions& options, bool adapt_knots = true);

class MethodState;  // fit_registry.h
/// IncrementalFit's fits (docs/method.md 7.7): run_fit() without the knot adaptation, the
/// method run as `state` (MethodEntry::incremental): update(changed) where `changed` is given
/// and the alignment leaves the rows in their order; otherwise fit() in full, and after rows
/// re-ordered by the alignment the state forgets (the next edit refits in full).
FitResult run_fit(const Rows& rows, const FitOptions& options, MethodState& state,
                  const std::vector<std::size_t>* changed);

/// Test hook: how many times sfit::validate() ran in this process.
long validations();

}  // namespace sfit::detail
