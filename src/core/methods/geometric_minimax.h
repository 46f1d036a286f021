// Minimax for the geometric rule where no pair held by least squares (docs/method.md 7.9).
// Private.
//
// PURPOSE  Noise near T: least squares follows the noise's peaks past T at every pair while a
//          smooth surface within T of every point exists (bench/scan_cases.py's
//          range_hole_noise at 1e-3, noise of 0.9 T: every pair up to the points failed and the
//          default kept the two stages' 200 x 150 for 21,319 points, folding).
// METHOD   The pairs the least-squares search solved that missed T by at most kLinfReach
//          (any miss under FitNorm::kLinf), fewest control points first, at most
//          kGeometricLinfTries of them and each with at most kGeometricLinfUnknowns control
//          points (where there is none: the pair missed least, if by at most
//          kGeometricLinfLooseReach): least squares on every point, then the minimax LP at the same
//          parameters (minimax_refine_points(): the coefficients the data hold weakly keep their
//          least-squares values), judged on every point with the rule's guards (near the
//          data where it is, no fold). At the search's base plane, then at the coordinate
//          plane (geometric_params.h) where that is another.
#pragma once

#include <functional>
#include <optional>

#include "geometric_params.h"
#include "geometric_search.h"
#include "pair_search.h"
#include "scattered_lsq.h"
#include "search_frame.h"

namespace sfit::detail {

inline constexpr int kGeometricLinfTries = 1;        // pairs per base plane
inline constexpr long kGeometricLinfUnknowns = 400;  // the LP's unknowns per axis, at most
// Where no pair missed by at most kLinfReach: the one least squares missed least, if by at
// most this. A surface within T at the pair (minimax max at most T) has least squares within
// (1 + L) T, L the least-squares projector's max-norm, at least 1 (and bounded for splines
// whatever the knots): a miss up to 2 T is what least squares gives where minimax may hold.
// (The noisy range image at 1e-3, seed 3: 19 x 19 missed by 1.40 T, minimax held T.)
inline constexpr double kGeometricLinfLooseReach = 2.0;

/// A least-squares surface of the rule at a pair: whether it held, the surface (empty: none
/// made) and its smoothness weight.
struct GeometricTry {
  bool holds = false;
  Surface s;
  double smoothing = 0;
};
using GeometricLeastSquares = std::function<GeometricTry(const ScatteredProblem&, int, int)>;

/// The minimax surface of the first near pair (of `searched`, below `bound`) that holds T at
/// every point and passes the guards; nullopt where none does, under FitNorm::kL2, or where
/// weights matter. `plane`: the base plane of `f`. Adds the pairs solved to `tried`.
std::optional<GeometricFit> geometric_minimax(const Frame& fr, const FitOptions& o,
                                              const ScatteredSpec& spec, const Fractions& f,
                                              const PairOracle& searched, long bound,
                                              BasePlane plane, const GeometricLeastSquares& ls,
                                              long& tried);

}  // namespace sfit::detail
