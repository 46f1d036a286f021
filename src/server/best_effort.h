// A file that does not fit at its T still opens in the editor, so it can be fixed: when the
// count search finds no surface within T (ErrorCode::kToleranceNotMet), the editor shows the
// surface at fixed counts (FitOptions::counts) that comes closest, its report saying NOT
// within T and the failing points marked; the next edit tries the full fit again.
#pragma once

#include <memory>
#include <string>

#include "sfit/incremental.h"
#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::server {

/// The fit of `rows` with `options`; where it throws kToleranceNotMet, the best surface found
/// instead: the fit at fixed counts, from the most control points the data can take (one per
/// point of the longest row, one per row) down, the first that solves (at the degrees the
/// rows can take where the options' cannot solve). `why` gets the full
/// fit's message then (empty when the full fit held). Other errors pass.
std::unique_ptr<IncrementalFit> fit_or_best_effort(Rows rows, const FitOptions& options,
                                                   std::string& why);

}  // namespace sfit::server
