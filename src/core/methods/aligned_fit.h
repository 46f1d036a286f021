// The seam hook of the fit (docs/seams.md): fits rows re-ordered by align_rows() and maps the
// result back onto the original points. Private to the fit frame.
#pragma once

#include "sfit/seam_alignment.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

/// The alignment FitOptions ask for (identity when both are keep).
RowAlignment alignment_for(const Rows& rows, const FitOptions& o);

/// Each row's seam offset (RowSeam::offset) when any is non-zero and the rows are closed;
/// empty otherwise.
std::vector<double> seam_offsets(const RowAlignment& a, bool closed_u);

/// Positions `f` (normalized_positions() of an aligned closed row) measured from the seam
/// `offset` point spacings past its first point, wrapped into [0, 1).
void shift_positions(std::vector<double>& f, double offset);

/// `fit` was made on apply_alignment(original, a): puts its u back in the order of
/// original.points(), names the worst point by its original index and records the seams
/// (composed with seams the method set on the aligned rows, where it set them).
void restore_original_order(FitResult& fit, const Rows& original, const RowAlignment& a);

}  // namespace sfit::detail
