// The editor's state: the rows, the fit that follows their edits (IncrementalFit), the
// quick refit of a drag, and undo/redo. Not thread-safe: the server serialises requests.
#pragma once

#include <cstddef>
#include <deque>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sfit/frozen_refit.h"
#include "sfit/incremental.h"
#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::server {

/// One undoable step: what it changed and what it replaced.
struct Change {
  enum class Kind { kRow, kInsertRow, kDeleteRow, kOptions };
  Kind kind = Kind::kRow;
  std::size_t row = 0;
  std::vector<Point> before, after;  ///< the row's points (kRow), the row (kInsert/kDeleteRow)
  FitOptions options_before, options_after;  ///< kOptions
  bool open = false;  ///< kOptions from a live control (a slider) that is still moving
};

/// Where a move stands in a drag.
enum class MovePhase {
  kOnce,  ///< a whole edit (typed coordinates, a script): full refit, one undo step
  kDrag,  ///< the hand moves: quick refit at the current counts, not final
  kRest,  ///< the hand rests: full refit of the current position; the drag goes on
  kEnd,   ///< the hand lets go: full refit; the whole drag is one undo step
};

class Session {
 public:
  /// Undo keeps at most this many steps (the oldest are dropped).
  static constexpr std::size_t kMaxUndo = 1000;

  /// Fits `rows` (Error as fit_surface() throws).
  Session(Rows rows, FitOptions options);
  ~Session();

  // Edits: each throws Error (kUsage for a place that does not exist, kInputData for data
  // the fit refuses) and leaves the state as it was.
  void move(std::size_t row, std::size_t index, const Point& to, MovePhase phase);
  void insert_point(std::size_t row, std::size_t index, const Point& p);
  void delete_point(std::size_t row, std::size_t index);
  void insert_row(std::size_t row, std::vector<Point> points);  ///< before `row` (M appends)
  void delete_row(std::size_t row);
  void replace_row(std::size_t row, std::vector<Point> points);
  /// New fit options (a full fit). kDrag: a live control moves (the T slider); consecutive
  /// kDrag changes and the kEnd that closes them are one undo step.
  void set_options(const FitOptions& options, MovePhase phase = MovePhase::kOnce);
  bool undo();  ///< false: nothing to undo
  bool redo();
  /// Ends an open drag where it is (full refit, one undo step); nothing without one.
  void finish_drag();

  /// What the page shows: the quick refit during a drag, else the full fit.
  const FitResult& shown() const;
  const Rows& shown_rows() const;
  /// True when shown() is the full fit (the fewest control points) of the current rows.
  bool final() const { return !drag_ || drag_->final; }
  bool dragging() const { return drag_.has_value(); }
  /// The full fit and its rows (during a drag: as of its start or last rest).
  const FitResult& result() const { return fit_->result(); }
  const Rows& rows() const { return fit_->rows(); }
  const FitOptions& options() const { return options_; }
  std::size_t undo_depth() const { return undo_.size(); }
  std::size_t redo_depth() const { return redo_.size(); }
  /// Counts every change of the shown surface.
  long version() const { return version_; }
  /// Rows whose curve stage the last refit redid (rows().size() for a full fit).
  std::size_t rows_refitted() const { return rows_refitted_; }
  /// Why the full fit (result()) is only the best surface found: the count search found none
  /// within T (its message; best_effort.h); empty when the full fit is the search's. Every
  /// edit tries the search again.
  const std::string& best_effort() const { return best_effort_; }
  /// The quick refit of a drag from the full fit as it is (sfit/frozen_refit.h), built once per
  /// full fit and kept until the fit changes (the influence of a selected point asks for it before
  /// the drag, which then starts without building it); nullptr with `why` where it cannot be
  /// made (the drag then refits at the counts by IncrementalFit, quick_refit.h).
  std::shared_ptr<const FrozenRefit> frozen(std::string* why = nullptr) const;

 private:
  struct Drag {
    std::size_t row = 0, index = 0;
    std::vector<Point> before;                  // the row at the start of the drag
    std::unique_ptr<IncrementalFit> quick;      // where no frozen refit could be made
    std::shared_ptr<const FrozenRefit> frozen;  // else: the refit frozen at the drag's start
    Rows rows;                                  // and its rows and result
    FitResult result;
    bool final = false;  // the last step was a rest: fit_ is at the current position
  };
  void apply(const Change& c, bool forward);
  // Row `row` becomes `points`: the incremental refit, or with a best-effort fit a full one.
  void set_row(std::size_t row, const std::vector<Point>& points);
  // fit_ becomes the fit of `rows` with `options` (the best effort where none holds T).
  void refit(Rows rows, const FitOptions& options);
  void commit(Change c);
  std::vector<Point> row_points(std::size_t row) const;
  // The drag's quick state: its rows, and point (row, index) moved to `to` with its refit.
  const Rows& drag_rows(const Drag& d) const { return d.quick ? d.quick->rows() : d.rows; }
  void drag_move(Drag& d, std::size_t row, std::size_t index, const Point& to);

  FitOptions options_;
  std::unique_ptr<IncrementalFit> fit_;
  std::optional<Drag> drag_;
  std::deque<Change> undo_, redo_;
  long version_ = 0;
  std::size_t rows_refitted_ = 0;
  std::string best_effort_;
  long fit_serial_ = 0;  // counts the changes of fit_ (the frozen refit's cache key)
  mutable std::shared_ptr<const FrozenRefit> frozen_;
  mutable std::string frozen_why_;
  mutable long frozen_serial_ = -1;
};

}  // namespace sfit::server
