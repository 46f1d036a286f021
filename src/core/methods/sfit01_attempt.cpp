// One attempt of the two-stage method at a stage budget (sfit01_attempt.h), and the centring
// it runs in.
#include "sfit01_attempt.h"

#include <algorithm>
#include <string_view>

#include "aligned_fit.h"
#include "common_count.h"
#include "curve_stage.h"
#include "fit_frame.h"
#include "fit_monitor.h"
#include "parallel.h"
#include "transverse_stage.h"

namespace sfit::detail {

void SurfaceFitter::centre(const Rows& rows) {
  if (given_) {  // the driver's centring of these rows (fit_aligned()): the same values
    threads_ = given_->threads;
    box_ = given_->box;
    centre_ = given_->centre;
    centred_ = &given_->centred;
    own_centred_ = Rows();
    centred_rows_ = centred_->size();
    roundoff_ = given_->roundoff;
    return;
  }
  threads_ = threads_for(rows, o_.threads);
  box_ = box_of(rows, threads_);
  centre_ = 0.5 * (box_.min + box_.max);
  copy_centred(rows);
  roundoff_ = kRoundoffRelative * box_.diagonal();
}

void SurfaceFitter::copy_centred(const Rows& rows) {
  own_centred_ = rows;
  parallel_for(rows.size(), threads_, [&](std::size_t j) {
    for (Point& p : own_centred_.mutable_row(j)) p -= centre_;
  });
  centred_ = nullptr;
  centred_rows_ = own_centred_.size();
}

SurfaceFitter::Attempt SurfaceFitter::fit_once(const Point& bound,
                                               const std::vector<char>* changed) {
  Attempt at;
  const Rows& rows = centred();
  const std::size_t M = rows.size();
  auto report = [&](std::string_view stage, std::size_t done, std::size_t total) {
    if (done == 0) {
      progress_phase(stage, total);
    } else {
      progress_advance(done);
    }
  };
  std::size_t longest = 0;
  for (std::size_t j = 0; j < M; ++j) longest = std::max(longest, rows[j].size());
  auto row_points = [&](std::size_t j) { return rows[j]; };

  // Positions of the points along their rows (none for the paper's rule): docs/method.md 7.4.
  const bool geometric = rule_ != Parametrization::kPaper;
  // Fractional seams (RowSeam::offset): positions measured from each row's seam
  // (the paper's rule then uses uniform positions, its own to rounding).
  const bool seam_positions = !row_seam_offsets_.empty();
  const bool row_geometric = geometric || seam_positions;
  std::vector<double> row_positions;
  if (row_geometric) {
    row_positions.resize(rows.total_points());
    parallel_for(M, threads_, [&](std::size_t j) {
      auto f =
          normalized_positions(rows[j], geometric ? rule_ : Parametrization::kUniform, o_.closed_u);
      if (seam_positions) shift_positions(f, row_seam_offsets_[j]);
      std::copy(f.begin(), f.end(),
                row_positions.begin() + static_cast<std::ptrdiff_t>(rows.offsets()[j]));
    });
  }
  auto row_positions_of = [&](std::size_t j) {
    if (!row_geometric) return std::span<const double>();
    return std::span<const double>(row_positions.data() + rows.offsets()[j], rows[j].size());
  };

  // Curve stage on the rows (docs/method.md 3): all rows, or the changed ones and their chains.
  report("rows", 0, M);
  CurveFitOptions row_options{o_.degree_u, o_.closed_u, bound, o_.search};
  // Uniform positions depend on the row's length only, so rows of one length share them.
  row_options.shared_positions = rule_ == Parametrization::kUniform;
  std::vector<CurveFit> fits;
  if (changed) fits = row_fits_;
  // Weighted rows: weighted least squares in the curve stage.
  const WeightsOf row_weights_of =
      rows.weighted() ? WeightsOf([&](std::size_t j) { return rows.row_weights(j); }) : WeightsOf();
  rows_refitted_ = fit_curves(M, row_points, row_positions_of, row_options, o_.row_count_hints,
                              threads_, fits, changed, row_weights_of);
  // `fast_fits` (the searches' own results) are what an update chains its hints from.
  std::vector<CurveFit> fast_fits;
  if (keep_state_) fast_fits = fits;
  exact_maximum(fits, row_points, row_positions_of, row_options, threads_, row_weights_of);
  // Rows whose fit changed need a new re-representation.
  std::vector<char> dirty(M, 1);
  if (changed)
    for (std::size_t j = 0; j < M; ++j)
      dirty[j] = (*changed)[j] || fits[j].curve.control != row_final_fits_[j].curve.control;
  report("rows", M, M);

  // Re-representation on the common count nu (docs/method.md 4).
  Represented rs =
      represent(M, row_points, row_positions_of, fits, o_.degree_u, o_.closed_u, bound, threads_,
                false, longest, {}, changed ? &row_curves_ : nullptr, row_common_,
                changed ? &dirty : nullptr, rows.weighted(), o_.rerepresentation);
  const int nu = rs.common;
  FitReport& r = at.report;
  r.row_counts.resize(M);
  r.solves = 0;
  for (std::size_t j = 0; j < M; ++j) {
    r.row_counts[j] = fits[j].curve.count();
    r.solves += fits[j].solves;
  }
  if (!keep_state_) std::vector<CurveFit>().swap(fits);  // re-represented: not needed further

  // Transverse stage: column i holds control point i of every row curve (docs/method.md 5).
  // The fold guard may set its own rule across the rows (across_). Its budget: the rows', or
  // with rows_take_all_ the half of the round-off allowance the rows left (interpolation).
  const Point column_bound = rows_take_all_ ? Point::Constant(0.5 * roundoff_) : bound;
  Columns columns =
      fit_columns(rows, rs.curves, nu, across_.value_or(rule_), o_, column_bound, threads_,
                  keep_state_ ? nullptr : &rs.curves);  // one shot: the rows' controls go
  const std::vector<CurveFit>& column_fits = columns.fits;
  const Represented& cs = columns.represented;
  const int nv = cs.common;

  Surface& s = at.surface;
  s.degree_u = o_.degree_u;
  s.degree_v = o_.degree_v;
  s.periodic_u = o_.closed_u;
  s.periodic_v = o_.closed_v;
  s.count_u = nu;
  s.count_v = nv;
  s.control.resize(static_cast<std::size_t>(nu) * nv);
  for (int i = 0; i < nu; ++i)
    for (int l = 0; l < nv; ++l) s.at(i, l) = cs.curves[i].curve.control[l];

  at.v = cs.shared_parameters;
  at.u.resize(rows.total_points());
  for (std::size_t j = 0; j < M; ++j)
    std::copy(rs.curves[j].parameters.begin(), rs.curves[j].parameters.end(),
              at.u.begin() + static_cast<std::ptrdiff_t>(rows.offsets()[j]));

  r.column_counts.resize(static_cast<std::size_t>(nu));
  for (int i = 0; i < nu; ++i) {
    r.column_counts[i] = column_fits[i].curve.count();
    r.solves += column_fits[i].solves;
  }
  r.raised_u = rs.common - rs.first_common;
  r.raised_v = cs.common - cs.first_common;
  r.repaired_rows = rs.repaired;
  r.repaired_columns = cs.repaired;

  // Keep the row stage for update(): fits, and re-representations at nu.
  if (keep_state_) {
    row_fits_ = std::move(fast_fits);
    row_final_fits_ = std::move(fits);
    row_curves_ = std::move(rs.curves);
    row_common_ = nu;
  }
  return at;
}

}  // namespace sfit::detail
