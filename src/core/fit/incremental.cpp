// IncrementalFit (sfit/incremental.h, docs/method.md 7.7): every fit through the driver
// (fit_driver.h); a method with a state in the registry (MethodEntry::incremental: the
// two-stage method) refits only the edited rows, any other refits in full.
#include "sfit/incremental.h"

#include <optional>
#include <string>

#include "fit_driver.h"
#include "fit_monitor.h"
#include "fit_registry.h"
#include "sfit/error.h"

namespace sfit {
namespace detail {

struct IncrementalState {
  FitOptions options;
  std::unique_ptr<MethodState> method;  // null: the method has none (every fit in full)
  std::size_t rows_refitted = 0;

  FitResult fit(const Rows& rows, const std::vector<std::size_t>* changed) {
    if (!method) {
      rows_refitted = rows.size();
      return run_fit(rows, options, false);  // fit_surface() without the knot adaptation
    }
    FitResult r = run_fit(rows, options, *method, changed);
    rows_refitted = method->rows_refitted();
    return r;
  }
};

}  // namespace detail

namespace {

[[noreturn]] void bad_place(const std::string& what, std::size_t row, std::size_t index) {
  throw Error(ErrorCode::kUsage, what,
              Place{.row = static_cast<long>(row), .point = static_cast<long>(index)});
}

// A copy of `rows` with row `row` replaced by `points`.
Rows with_row(const Rows& rows, std::size_t row, std::span<const Point> points) {
  Rows out;
  out.reserve(rows.total_points() + points.size(), rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (const Point& p : j == row ? points : rows[j]) out.push_point(p);
    out.end_row();
  }
  return out;
}

// Runs `f` with the progress and cancel of `o` watched (FitOptions::progress, ::cancel), as
// fit_surface() does.
template <class F>
FitResult monitored(const FitOptions& o, F&& f) {
  std::optional<detail::FitMonitor> monitor;
  if (detail::FitMonitor::wanted(o) && !detail::current_monitor()) monitor.emplace(o);
  const detail::MonitorScope scope(monitor ? &*monitor : detail::current_monitor());
  return f();
}

}  // namespace

IncrementalFit::IncrementalFit(Rows rows, FitOptions options)
    : rows_(std::move(rows)), state_(std::make_unique<detail::IncrementalState>()) {
  // The method's state from the registry (the driver's options: seam and orient kKeep).
  // An unregistered method is the driver's usage error, after the rows' validation.
  for (const detail::MethodEntry& e : detail::methods())
    if (e.id == options.method && e.incremental) {
      FitOptions mo = options;
      mo.seam = SeamMode::kKeep;
      mo.orient = OrientMode::kKeep;
      state_->method = e.incremental(mo);
    }
  state_->options = std::move(options);
  result_ = monitored(state_->options, [&] { return state_->fit(rows_, nullptr); });
}

IncrementalFit::~IncrementalFit() = default;
IncrementalFit::IncrementalFit(IncrementalFit&&) noexcept = default;
IncrementalFit& IncrementalFit::operator=(IncrementalFit&&) noexcept = default;

std::size_t IncrementalFit::rows_refitted() const {
  return state_->rows_refitted;
}

const FitResult& IncrementalFit::apply(Rows edited, std::size_t row) {
  // Edits do not carry per-point weights yet: refuse rather than drop them.
  if (rows_.weighted())
    throw Error(ErrorCode::kUsage, "edits of weighted rows are not supported yet",
                Place{.option = "weights"});
  // Throws before touching the state (a cancelled edit too).
  const std::vector<std::size_t> changed{row};
  FitResult r = monitored(state_->options, [&] { return state_->fit(edited, &changed); });
  rows_ = std::move(edited);
  result_ = std::move(r);
  return result_;
}

const FitResult& IncrementalFit::move_point(std::size_t row, std::size_t index, const Point& to) {
  if (row >= rows_.size() || index >= rows_[row].size())
    bad_place("no such point to move", row, index);
  std::vector<Point> points(rows_[row].begin(), rows_[row].end());
  points[index] = to;
  return apply(with_row(rows_, row, points), row);
}

const FitResult& IncrementalFit::insert_point(std::size_t row, std::size_t index, const Point& p) {
  if (row >= rows_.size() || index > rows_[row].size())
    bad_place("no such place to insert a point", row, index);
  std::vector<Point> points(rows_[row].begin(), rows_[row].end());
  points.insert(points.begin() + static_cast<std::ptrdiff_t>(index), p);
  return apply(with_row(rows_, row, points), row);
}

const FitResult& IncrementalFit::erase_point(std::size_t row, std::size_t index) {
  if (row >= rows_.size() || index >= rows_[row].size())
    bad_place("no such point to delete", row, index);
  if (rows_[row].size() == 1) bad_place("a row keeps at least one point", row, index);
  std::vector<Point> points(rows_[row].begin(), rows_[row].end());
  points.erase(points.begin() + static_cast<std::ptrdiff_t>(index));
  return apply(with_row(rows_, row, points), row);
}

const FitResult& IncrementalFit::replace_row(std::size_t row, std::span<const Point> points) {
  if (row >= rows_.size()) bad_place("no such row to replace", row, 0);
  if (points.empty()) bad_place("a row keeps at least one point", row, 0);
  return apply(with_row(rows_, row, points), row);
}

}  // namespace sfit
