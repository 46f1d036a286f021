// One attempt of the two-stage method (FitMethod::kSfit01) at a stage budget: the curve stage
// on the rows (curve_stage.h), their re-representation on the common count nu
// (common_count.h), the transverse stage (transverse_stage.h), in centred coordinates
// (SurfaceFitter::fit_once(), sfit01_attempt.cpp). The driver (sfit01_method.cpp) checks,
// tightens and finishes it. Private to the two-stage method.
#pragma once

#include <vector>

#include "sfit/surface_fit.h"
#include "surface_fitter.h"

namespace sfit::detail {

struct SurfaceFitter::Attempt {
  Surface surface;  // centred coordinates
  std::vector<double> u, v;
  FitReport report;
};

}  // namespace sfit::detail
