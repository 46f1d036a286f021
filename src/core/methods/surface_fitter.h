// The two-stage method (FitMethod::kSfit01) as a state that can be updated after edits of some
// rows (docs/method.md 7.7). Private: the registry runs it (fit_registry.cpp), IncrementalFit
// through sfit01_state() (a MethodState, fit_registry.h) under the driver.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "fit_driver.h"
#include "fit_registry.h"
#include "rerepresent.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

/// The methods as the registry (fit_registry.cpp) runs them: FitMethod::kSurface
/// (surface_method.cpp) and FitMethod::kSfit01 (SurfaceFitter below, sfit01_method.cpp).
FitResult fit_surface_search(const FitSpec& spec);
FitResult fit_sfit01_method(const FitSpec& spec);
/// kSfit01's state for IncrementalFit (MethodEntry::incremental): a SurfaceFitter.
std::unique_ptr<MethodState> sfit01_state(const FitOptions& options);

class SurfaceFitter {
 public:
  /// kAuto parameters are the paper's for kSfit01 (SFIT01's rule).
  explicit SurfaceFitter(FitOptions options) : o_(std::move(options)) {
    if (o_.method == FitMethod::kSfit01 && o_.parametrization == Parametrization::kAuto)
      o_.parametrization = Parametrization::kPaper;
  }

  const FitOptions& options() const { return o_; }
  /// The same result as fit_aligned(rows, {}, &centring) after the rows in `changed` were
  /// edited (the number of rows unchanged, not re-ordered), refitting only what the edit
  /// touches: the edited rows, later rows of their block whose starting count changed, and
  /// their re-representations; the transverse stage and the check are redone as the fit does
  /// them. Falls back to the fit in full where reuse is not exact: a changed bounding box (the
  /// centring changes), a tightened budget, no state (forget()).
  FitResult update_aligned(const Rows& rows, const std::vector<std::size_t>& changed,
                           const Centring& centring);
  /// The next update_aligned() fits in full.
  void forget() { valid_ = false; }
  /// The method on rows validated and aligned already, with their fractional seams and, where
  /// given, their centring (of these very rows: the driver's); no final check (the driver's).
  FitResult fit_aligned(const Rows& rows, std::span<const double> seam_offsets,
                        const Centring* centring = nullptr) {
    const EndOfFit end{*this};
    row_seam_offsets_.assign(seam_offsets.begin(), seam_offsets.end());
    given_ = centring;
    return fit_given(rows);
  }
  /// false: a one-shot fit (no update_aligned() follows): the row stage is not kept for
  /// updates, and the row fits are released before the transverse stage (less memory).
  void keep_state(bool on) { keep_state_ = on; }
  /// Rows refitted by the last fit_aligned() or update_aligned().
  std::size_t rows_refitted() const { return rows_refitted_; }
  /// The stage budgets. false (the paper's): T/2 for the rows and T/2 for the columns. true:
  /// all of T for the rows, and the columns interpolate the rows' control points (the
  /// transverse stage at the round-off allowance, nv = the number of rows). Where the data
  /// jumps from row to row (roofs and trees in airborne LiDAR) the columns interpolate anyway,
  /// and half of T spent on them is lost to the rows.
  void rows_take_all(bool on) { rows_take_all_ = on; }

 private:
  struct Attempt;
  FitResult fit_given(const Rows& rows);  // the fit on rows as given (aligned already)
  FitResult fit_rule(const Rows& rows, Parametrization requested);
  FitResult fit_rule_unguarded(const Rows& rows, Parametrization requested);  // no fold guard
  bool folds(const FitResult& r) const;
  FitResult fit_with_rule(const Rows& rows);
  // `bound`: the row stage's budget; the transverse stage's is the same, or with
  // rows_take_all_ the round-off allowance's half.
  Attempt fit_once(const Point& bound, const std::vector<char>* changed);
  FitResult finish(Attempt& at, int tightenings, const struct DeviationCheck& check,
                   double seconds_start) const;
  void centre(const Rows& rows);
  void copy_centred(const Rows& rows);  // own_centred_ = rows - centre_
  // The centred rows of the fit running: the driver's (given_, or update_aligned()'s centring;
  // no copy of the points) or the fitter's own copy.
  const Rows& centred() const { return centred_ ? *centred_ : own_centred_; }

  FitOptions o_;
  Parametrization rule_ = Parametrization::kPaper;  // the rule of the last fit
  int threads_ = 1;
  BoundingBox box_;
  Point centre_ = Point::Zero();
  double roundoff_ = 0;
  Rows own_centred_;
  const Rows* centred_ = nullptr;  // valid during a fit or an update only
  // Drops what a fit or an update borrowed from its caller (the seams, the driver's centring
  // and centred rows) when it returns or throws, so nothing dangles after it.
  struct EndOfFit {
    SurfaceFitter& f;
    ~EndOfFit() {
      f.row_seam_offsets_.clear();
      f.given_ = nullptr;
      f.centred_ = nullptr;
    }
  };
  std::size_t centred_rows_ = 0;  // the last fit's rows (update_aligned() compares)
  // State of the first (untightened) attempt of the last fit, reused by update().
  bool valid_ = false;
  Point bound_ = Point::Zero();
  bool rows_take_all_ = false;            // rows_take_all()
  bool keep_state_ = true;                // keep_state()
  std::vector<CurveFit> row_fits_;        // the count searches' results (hints chain from them)
  std::vector<CurveFit> row_final_fits_;  // after exact_maximum(): what was re-represented
  std::vector<Rerepresentation> row_curves_;
  int row_common_ = 0;
  std::size_t rows_refitted_ = 0;
  std::vector<double> row_seam_offsets_;   // fractional seams of the rows being fitted
  const Centring* given_ = nullptr;        // the driver's centring of the rows fitted
  std::optional<Parametrization> across_;  // the fold guard's rule across the rows
  bool degree_lowered_ = false;            // the fold guard's fit one degree lower across
};

}  // namespace sfit::detail
