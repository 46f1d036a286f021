// The limits and defaults of the fit's options, owned by the library: the CLI, the editor and
// the Python module check their options with these functions and never restate the numbers.
#pragma once

#include <string>

#include "sfit/rows.h"

namespace sfit {

inline constexpr int kMinFitDegree = 1;
inline constexpr int kMaxFitDegree = 20;  ///< the basis evaluators' kMaxDegree
/// Threads a fit may ask for (0: all cores); more than this is refused, not attempted.
inline constexpr int kMaxThreads = 256;
/// The default tolerance: this fraction of the data's bounding-box diagonal on every axis.
inline constexpr double kDefaultToleranceFraction = 1e-3;

/// Each throws Error(kUsage) naming `option` and the value, with the allowed range.
void check_degree(int degree, const std::string& option);
void check_threads(int threads, const std::string& option);
/// A fraction 0 ... 1 of the bounding-box diagonal.
void check_tolerance_fraction(double fraction, const std::string& option);
/// Each component finite and >= 0.
void check_tolerance(const Point& tolerance, const std::string& option);

}  // namespace sfit
