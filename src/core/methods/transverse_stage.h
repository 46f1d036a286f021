// The transverse stage (docs/method.md 5) of the two-stage method (FitMethod::kSfit01): column
// i holds control point i of every row curve; the columns get the curve stage's count searches
// and the re-representation on a common count nv, at one position per row shared by every
// column. Private to the two-stage method (sfit01_*.cpp).
#pragma once

#include <vector>

#include "common_count.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

/// The columns' minimal fits and their re-representation on the common count nv.
struct Columns {
  std::vector<CurveFit> fits;
  Represented represented;
};

/// The transverse stage on `row_curves` (the rows' curves on the common count `nu`, fitted to
/// `rows`), each column within `bound` per axis, at the positions of the rule `across`
/// (kPaper: the paper's parameters) averaged over the columns. Weighted rows weigh the
/// columns' points (docs/seams.md). Reports progress as "columns" through o.progress.
/// `release` (the very vector `row_curves`, or null): its curves' control points are freed
/// once copied into the columns, for a caller that needs them no further (less memory).
Columns fit_columns(const Rows& rows, const std::vector<Rerepresentation>& row_curves, int nu,
                    Parametrization across, const FitOptions& o, const Point& bound, int threads,
                    std::vector<Rerepresentation>* release = nullptr);

}  // namespace sfit::detail
