#include "session.h"

#include <string>

#include "best_effort.h"
#include "quick_refit.h"
#include "sfit/error.h"

namespace sfit::server {
namespace {

[[noreturn]] void no_such(const std::string& what, std::size_t row, long index = -1) {
  throw Error(ErrorCode::kUsage, what, Place{.row = static_cast<long>(row), .point = index});
}

// `rows` with row `row` removed (erase) or `points` inserted before it.
Rows edited_rows(const Rows& rows, std::size_t row, const std::vector<Point>* insert) {
  Rows out;
  out.reserve(rows.total_points() + (insert ? insert->size() : 0), rows.size() + 1);
  for (std::size_t j = 0; j <= rows.size(); ++j) {
    if (j == row && insert) out.add_row(*insert);
    if (j < rows.size() && (j != row || insert)) out.add_row(rows[j]);
  }
  return out;
}

// `rows` with row `row` replaced by `points`.
Rows with_row(const Rows& rows, std::size_t row, const std::vector<Point>& points) {
  Rows out;
  out.reserve(rows.total_points() + points.size(), rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) out.add_row(j == row ? points : rows[j]);
  return out;
}

}  // namespace

Session::Session(Rows rows, FitOptions options) : options_(std::move(options)) {
  refit(std::move(rows), options_);
}

void Session::refit(Rows rows, const FitOptions& options) {
  ++fit_serial_;
  std::string why;
  fit_ = fit_or_best_effort(std::move(rows), options, why);
  best_effort_ = std::move(why);
  rows_refitted_ = fit_->rows_refitted();
}

void Session::set_row(std::size_t row, const std::vector<Point>& points) {
  ++fit_serial_;
  if (best_effort_.empty()) {
    try {
      fit_->replace_row(row, points);
      rows_refitted_ = fit_->rows_refitted();
      return;
    } catch (const Error& e) {
      if (e.code() != ErrorCode::kToleranceNotMet) throw;
    }
  }
  if (points.empty()) no_such("a row keeps at least one point", row);
  if (fit_->rows().weighted())  // as IncrementalFit's edits: refused, not weights dropped
    throw Error(ErrorCode::kUsage, "edits of weighted rows are not supported yet",
                Place{.option = "weights"});
  refit(with_row(fit_->rows(), row, points), options_);
}

Session::~Session() = default;

const FitResult& Session::shown() const {
  if (!drag_ || drag_->final) return fit_->result();
  return drag_->quick ? drag_->quick->result() : drag_->result;
}

const Rows& Session::shown_rows() const {
  return drag_ && !drag_->final ? drag_rows(*drag_) : fit_->rows();
}

std::shared_ptr<const FrozenRefit> Session::frozen(std::string* why) const {
  if (frozen_serial_ != fit_serial_) {
    frozen_ = FrozenRefit::make(fit_->rows(), fit_->result(), frozen_why_);
    frozen_serial_ = fit_serial_;
  }
  if (why) *why = frozen_ ? std::string() : frozen_why_;
  return frozen_;
}

void Session::drag_move(Drag& d, std::size_t row, std::size_t index, const Point& to) {
  if (d.quick) {
    d.quick->move_point(row, index, to);
    rows_refitted_ = d.quick->rows_refitted();
    return;
  }
  if (!to.allFinite())  // as fit_surface() refuses it; the state stays as it was
    throw Error(ErrorCode::kInputData, "coordinate is not a finite number",
                Place{.row = static_cast<long>(row), .point = static_cast<long>(index)},
                {to.x(), to.y(), to.z()});
  d.rows.mutable_row(row)[index] = to;
  d.result = d.frozen->refit(d.rows);
  rows_refitted_ = d.rows.size();  // one solve for the whole surface
}

std::vector<Point> Session::row_points(std::size_t row) const {
  const auto r = fit_->rows()[row];
  return {r.begin(), r.end()};
}

void Session::commit(Change c) {
  if (!undo_.empty()) undo_.back().open = false;
  undo_.push_back(std::move(c));
  if (undo_.size() > kMaxUndo) undo_.pop_front();
  redo_.clear();
  ++version_;
}

void Session::move(std::size_t row, std::size_t index, const Point& to, MovePhase phase) {
  if (drag_ && (drag_->row != row || drag_->index != index)) finish_drag();
  const Rows& rows = fit_->rows();
  if (row >= rows.size() || index >= rows[row].size()) no_such("no such point to move", row, index);
  if (phase == MovePhase::kOnce) {
    std::vector<Point> before = row_points(row), after = before;
    after[index] = to;
    set_row(row, after);
    commit(Change{.kind = Change::Kind::kRow,
                  .row = row,
                  .before = std::move(before),
                  .after = row_points(row)});
    return;
  }
  if (!drag_) {
    Drag d;
    d.row = row;
    d.index = index;
    d.before = row_points(row);
    // The counts, knots and parameters of the full fit, frozen for the drag (sfit/frozen_refit.h);
    // where that cannot be made, the refit at its counts (quick_refit.h).
    d.frozen = frozen();
    if (d.frozen) {
      d.rows = fit_->rows();
      d.result = fit_->result();  // shown until the first step's refit (which may refuse it)
    } else
      d.quick = std::make_unique<IncrementalFit>(
          fit_->rows(), quick_refit_options(options_, fit_->result().report));
    drag_ = std::move(d);
  }
  Drag& d = *drag_;
  if (phase == MovePhase::kDrag) {
    drag_move(d, row, index, to);
    d.final = false;
    ++version_;
    return;
  }
  // kRest and kEnd: the full fit at the hand's position (the quick state follows it too).
  if (fit_->rows()[row][index] != to) {
    std::vector<Point> after = row_points(row);
    after[index] = to;
    set_row(row, after);
  }
  if (drag_rows(d)[row][index] != to) drag_move(d, row, index, to);
  d.final = true;
  ++version_;
  if (phase == MovePhase::kEnd) finish_drag();
}

void Session::finish_drag() {
  if (!drag_) return;
  Drag d = std::move(*drag_);
  drag_.reset();
  const Point to = drag_rows(d)[d.row][d.index];
  if (fit_->rows()[d.row][d.index] != to) {
    try {
      std::vector<Point> after = row_points(d.row);
      after[d.index] = to;
      set_row(d.row, after);
    } catch (...) {
      // The full fit refuses where the quick one took it: the drag is dropped.
      if (row_points(d.row) != d.before) set_row(d.row, d.before);
      ++version_;
      throw;
    }
  }
  std::vector<Point> after = row_points(d.row);
  if (after == d.before) {
    ++version_;
    return;
  }
  commit(Change{.kind = Change::Kind::kRow,
                .row = d.row,
                .before = std::move(d.before),
                .after = std::move(after)});
}

void Session::insert_point(std::size_t row, std::size_t index, const Point& p) {
  finish_drag();
  if (row >= rows().size()) no_such("no such row to insert a point in", row);
  std::vector<Point> before = row_points(row), after = before;
  if (index > after.size()) no_such("no such place to insert a point", row, index);
  after.insert(after.begin() + static_cast<std::ptrdiff_t>(index), p);
  set_row(row, after);
  commit(Change{.kind = Change::Kind::kRow,
                .row = row,
                .before = std::move(before),
                .after = row_points(row)});
}

void Session::delete_point(std::size_t row, std::size_t index) {
  finish_drag();
  if (row >= rows().size()) no_such("no such row to delete a point from", row);
  std::vector<Point> before = row_points(row), after = before;
  if (index >= after.size()) no_such("no such point to delete", row, index);
  if (after.size() == 1) no_such("a row keeps at least one point", row, index);
  after.erase(after.begin() + static_cast<std::ptrdiff_t>(index));
  set_row(row, after);
  commit(Change{.kind = Change::Kind::kRow,
                .row = row,
                .before = std::move(before),
                .after = row_points(row)});
}

void Session::replace_row(std::size_t row, std::vector<Point> points) {
  finish_drag();
  if (row >= rows().size()) no_such("no such row to replace", row);
  Change c{.kind = Change::Kind::kRow,
           .row = row,
           .before = row_points(row),
           .after = std::move(points)};
  apply(c, true);
  commit(std::move(c));
}

void Session::insert_row(std::size_t row, std::vector<Point> points) {
  finish_drag();
  if (row > rows().size()) no_such("no such place to insert a row", row);
  if (points.empty()) no_such("a row needs at least one point", row);
  Change c{.kind = Change::Kind::kInsertRow, .row = row, .after = std::move(points)};
  apply(c, true);
  commit(std::move(c));
}

void Session::delete_row(std::size_t row) {
  finish_drag();
  if (row >= rows().size()) no_such("no such row to delete", row);
  Change c{.kind = Change::Kind::kDeleteRow, .row = row, .before = row_points(row)};
  apply(c, true);
  commit(std::move(c));
}

void Session::set_options(const FitOptions& options, MovePhase phase) {
  finish_drag();
  const bool live = phase == MovePhase::kDrag || phase == MovePhase::kRest;
  Change c{.kind = Change::Kind::kOptions, .options_before = options_, .options_after = options};
  apply(c, true);
  if (!undo_.empty() && undo_.back().kind == Change::Kind::kOptions && undo_.back().open &&
      redo_.empty()) {
    undo_.back().options_after = options;  // the same slider movement
    undo_.back().open = live;
    ++version_;
    return;
  }
  c.open = live;
  commit(std::move(c));
}

// Applies `c` (forward) or its inverse; the state changes only if the refit succeeds.
void Session::apply(const Change& c, bool forward) {
  using K = Change::Kind;
  switch (c.kind) {
    case K::kRow:
      set_row(c.row, forward ? c.after : c.before);
      return;
    case K::kInsertRow:
    case K::kDeleteRow: {
      if (fit_->rows().weighted())  // as IncrementalFit's edits: refused, not weights dropped
        throw Error(ErrorCode::kUsage, "edits of weighted rows are not supported yet",
                    Place{.option = "weights"});
      const bool insert = (c.kind == K::kInsertRow) == forward;
      const std::vector<Point>& points = c.kind == K::kInsertRow ? c.after : c.before;
      refit(edited_rows(fit_->rows(), c.row, insert ? &points : nullptr), options_);
      return;
    }
    case K::kOptions: {
      const FitOptions& o = forward ? c.options_after : c.options_before;
      refit(fit_->rows(), o);
      options_ = o;
      return;
    }
  }
}

bool Session::undo() {
  finish_drag();
  if (undo_.empty()) return false;
  undo_.back().open = false;
  apply(undo_.back(), false);
  redo_.push_back(std::move(undo_.back()));
  undo_.pop_back();
  ++version_;
  return true;
}

bool Session::redo() {
  finish_drag();
  if (redo_.empty()) return false;
  apply(redo_.back(), true);
  undo_.push_back(std::move(redo_.back()));
  redo_.pop_back();
  ++version_;
  return true;
}

}  // namespace sfit::server
