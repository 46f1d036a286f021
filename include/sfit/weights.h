// The range of a point's weight (docs/seams.md), which every reader and fit_surface() check.
#pragma once

#include <string>

namespace sfit {

/// A weight is a relative importance within 1e-6 ... 1e6. Beyond it the weighted
/// least-squares systems lose their digits (a weight of 1e50 swamps every other term, a
/// subnormal one vanishes) and would be refused as singular.
inline constexpr double kMinWeight = 1e-6;
inline constexpr double kMaxWeight = 1e6;

/// Empty if `w` is a valid weight (kMinWeight ... kMaxWeight), else why not, e.g.
/// "weight must be a number 1e-06 ... 1e+06, got 1e+50".
std::string weight_error(double w);

}  // namespace sfit
