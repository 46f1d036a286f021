// Curve stage: one row of points to the B-spline curve with the fewest control points that
// keeps every component of every point within a bound (docs/method.md section 3).
#pragma once

#include <string_view>

#include <span>
#include <vector>

#include "sfit/curve.h"
#include "sfit/rows.h"

namespace sfit {

/// How a row curve is re-represented on the common count (docs/seams.md): sampled at the
/// paper's parameters, or at equal arc length (open curves; a closed one keeps the paper's).
enum class Resampling { kPaper, kArcLength };
std::string_view to_string(Resampling r);  ///< "paper", "arc_length"
bool parse_resampling(std::string_view name, Resampling& out);

/// How the smallest control-point count is searched (docs/method.md section 7.1).
enum class CountSearch {
  kLinear,  ///< the paper's SFIT01: count = degree+1, degree+2, ... until the fit holds; the
            ///< smallest count that holds
  kFast,    ///< default: from a starting count (the hint, e.g. the neighbouring row's count),
            ///< gallop down or up, then bisect, to a count that holds while the one below does
            ///< not. Equal to kLinear where holding is monotone in the count; README "Count
            ///< search" says where it is not and by how much the counts differ there.
  kKnown,   ///< take the hint as the count (one solve); if it does not hold, search as kFast.
            ///< The oracle of bench/: what the fit costs when the counts are known.
};

/// A least-squares curve and what it achieved.
struct CurveFit {
  Curve curve;
  std::vector<double> parameters;  ///< t of each data point
  /// true: `parameters` are scaled_parameters() of the positions the fit was given
  /// (docs/method.md 7.4); false: the paper's (paper_parameters()), also where the positions
  /// could not be used (an interpolant they make singular).
  bool scaled = false;
  Point max_deviation = Point::Zero();  ///< max_j |C(t_j) - D_j| per axis
  int solves = 0;                       ///< least-squares solves the search needed
};

/// Least-squares fit of `points` by a uniform curve of `degree` with exactly `count` control
/// points at the paper's parameters (docs/method.md 3), or, given `positions`
/// (normalized_positions()), at their scaled_parameters(). Requires degree+1 <= count <=
/// points.size() (a periodic fit needs count >= degree + 1 too). Throws Error(kInternal) if
/// the system is singular, which the paper's parameters rule out (positions may not).
/// With `weights` (one > 0 per point; empty: all 1) the fit minimises sum w_j |C(t_j) - D_j|^2
/// (weighted least squares: each equation scaled by sqrt(w_j)).
CurveFit fit_curve_with_count(std::span<const Point> points, int degree, bool periodic, int count,
                              std::span<const double> positions = {},
                              std::span<const double> weights = {});

struct CurveFitOptions {
  int degree = 3;
  bool periodic = false;        ///< closed contour (first point not repeated at the end)
  Point bound = Point::Zero();  ///< per-axis bound on |C(t_j) - D_j| (T/2 in a surface fit)
  CountSearch search = CountSearch::kFast;
  int hint = 0;  ///< where kFast starts, the count kKnown takes; 0: degree + 1
  /// Positions of the points (normalized_positions()) for the rules of docs/method.md 7.4; empty:
  /// the paper's parameters. A count whose system the positions leave singular does not hold;
  /// at count N (interpolation) the paper's parameters are the fallback.
  std::span<const double> positions;
  /// The positions are shared by many curves (all columns, rows of one length at uniform
  /// positions): worth caching their factorisations.
  bool shared_positions = false;
  /// Weights of the points (docs/seams.md): weighted least squares; empty: all 1, and the
  /// shared factorisations are used. The bound stays a hard bound for every point.
  std::span<const double> weights;
  /// CountSearch::kLinear only: try at most this many counts (0: no limit). Where none of
  /// them holds the fit comes back without control points: every count below
  /// degree + 1 + linear_limit fails, a lower bound on the smallest one that holds.
  int linear_limit = 0;
};

/// The curve with the smallest count in [degree+1, N] whose fit keeps every point within
/// `bound` per axis; count N interpolates and is accepted as the last resort.
/// A row of 1 < N < degree+1 points gives its degree N-1 interpolant (the paper's order-N
/// curve); a row of 1 point gives a constant curve of degree 0 (a pole).
CurveFit fit_curve(std::span<const Point> points, const CurveFitOptions& options);

/// Checks one row and the options before fit_curve() for callers that fit a row on its own
/// (fit_surface() validates its rows itself): at least one point, every coordinate finite, a
/// closed row of 1 or >= 3 points, degree 1 ... kMaxDegree, the bound finite and >= 0, and no
/// positions of the wrong length. Throws Error (kInputData for the points, kUsage for the
/// options, naming the option as `degree`, `tol`, `positions`).
void validate_curve(std::span<const Point> points, const CurveFitOptions& options);

}  // namespace sfit
