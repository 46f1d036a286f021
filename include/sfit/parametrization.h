// The rules that give data points their parameters (docs/method.md section 3 step 3 and 7.4),
// and the positions of a row's points they start from. The parameters of a given count and the
// re-representation map are private (src/core/spline/parameters.h).
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "sfit/rows.h"

namespace sfit {

/// How the data points of a row (or the rows, across) get their parameters: the built-in rules;
/// a rule registered at run time has an id beyond these (docs/method.md 7.11), which
/// to_string(), parse_parametrization() and normalized_positions() know while it is registered.
enum class Parametrization {
  kPaper,        ///< docs/method.md 3: the Greville sequence read at the point's index (SFIT01)
  kUniform,      ///< docs/method.md 7.4: equal steps in the point's index, t = L j / (N-1)
  kChord,        ///< docs/method.md 7.4: proportional to the chord length along the row
  kCentripetal,  ///< docs/method.md 7.4: proportional to the square root of the chord length
  /// docs/method.md 7.9: each point's (u, v) from its projection onto a base surface (the best
  /// plane of the points; for closed rows an axis through the rows' centroids, u the angle
  /// around it), corrected by projection onto the fit. v differs along a row
  /// (FitResult::v_points). The surface method (FitMethod::kSurface) only; not a curve rule.
  kGeometric,
  /// Not a rule: fit_surface() tries the four above and keeps the surface with the fewest
  /// control points (the report names the rule used). Costs the four fits.
  kFewest,
  /// Not a rule: the fit method's own choice (FitOptions::method): kPaper for the two-stage
  /// method (FitMethod::kSfit01, as SFIT01); for the surface search kGeometric and the four
  /// rules, keeping the surface with the fewest control points.
  kAuto,
};

/// "paper", "uniform", "chord", "centripetal", "geometric", "fewest", "auto".
std::string_view to_string(Parametrization p);
/// The inverse of to_string(); false if `name` is none of them.
bool parse_parametrization(std::string_view name, Parametrization& out);

/// Positions f_0 ... f_{N-1} of a row's points as fractions of the row, for the rules other
/// than kPaper: open rows from f_0 = 0 to f_last = 1, closed rows from f_0 = 0 up to below 1
/// (the closing chord, last point back to the first, counts). A row whose points all coincide
/// gets uniform positions.
std::vector<double> normalized_positions(std::span<const Point> points, Parametrization rule,
                                         bool periodic);

}  // namespace sfit
