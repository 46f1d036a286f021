// Refitting after a small edit of the data (docs/method.md 7.6-7.7): the designer moves, adds or
// deletes a data point, or replaces a row, and the surface follows.
#pragma once

#include <memory>
#include <span>

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit {

namespace detail {
struct IncrementalState;
}

/// A fitted state that follows edits of its rows. Every edit returns exactly what
/// fit_surface() returns for the edited rows and the same options (bit for bit), but refits
/// only what the edit touches: the edited row's curve stage (and the rows after it in its
/// block of 16 whose starting count it changed) and their re-representations; the other rows'
/// results are reused while the common count nu stays. The transverse stage and the check of
/// every point are redone. An edit that changes the bounding box changes the centring and so
/// costs a full fit, as does one after which the first attempt misses the tolerance.
/// Edits are validated like fit_surface() input (Error on a bad one; the state is unchanged).
class IncrementalFit {
 public:
  /// Fits `rows` with `options` (options.tolerance is absolute and stays fixed).
  IncrementalFit(Rows rows, FitOptions options);
  ~IncrementalFit();
  IncrementalFit(IncrementalFit&&) noexcept;
  IncrementalFit& operator=(IncrementalFit&&) noexcept;

  const FitResult& result() const { return result_; }
  const Rows& rows() const { return rows_; }

  /// Moves point `index` of row `row` to `to`.
  const FitResult& move_point(std::size_t row, std::size_t index, const Point& to);
  /// Inserts `p` before point `index` of row `row` (index == row size appends).
  const FitResult& insert_point(std::size_t row, std::size_t index, const Point& p);
  /// Deletes point `index` of row `row` (a row keeps at least one point).
  const FitResult& erase_point(std::size_t row, std::size_t index);
  /// Replaces row `row` by `points` (at least one).
  const FitResult& replace_row(std::size_t row, std::span<const Point> points);

  /// Rows whose curve stage the last edit refitted (rows().size() after a full fit).
  std::size_t rows_refitted() const;

 private:
  const FitResult& apply(Rows edited, std::size_t row);
  Rows rows_;
  std::unique_ptr<detail::IncrementalState> state_;
  FitResult result_;
};

}  // namespace sfit
