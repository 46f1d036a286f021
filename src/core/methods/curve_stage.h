// The curve stage's count searches (docs/method.md 3) of the two-stage method
// (FitMethod::kSfit01), on the rows and on the columns alike: every curve's minimal fit, each
// search starting from its block predecessor's count (fit_curves()), then the largest count
// made the paper's (exact_maximum()). Private to the two-stage method (sfit01_*.cpp).
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "sfit/curve_fit.h"

namespace sfit::detail {

/// Curve i's points, its positions (empty: the paper's parameters), its points' weights
/// (docs/seams.md; an empty function: unweighted).
using PointsOf = std::function<std::span<const Point>(std::size_t)>;
using PositionsOf = std::function<std::span<const double>(std::size_t)>;
using WeightsOf = std::function<std::span<const double>(std::size_t)>;

/// The minimal fits of curves `todo` (sorted), each starting from its block predecessor's
/// count (or from `hints`). Fixed blocks make the result independent of the thread count.
/// With `previous` (fits of an earlier pass over the same curves), a curve not in `todo`
/// keeps its previous fit unless its predecessor's count changed, in which case it is
/// refitted too, exactly as a full pass would. Returns how many curves were fitted.
std::size_t fit_curves(std::size_t n_curves, const PointsOf& points_of,
                       const PositionsOf& positions_of, const CurveFitOptions& base,
                       const std::vector<int>& hints, int threads, std::vector<CurveFit>& fits,
                       const std::vector<char>* todo, const WeightsOf& weights_of = {});

/// Makes the largest count of `fits` the paper's (CountSearch::kLinear) where the search was
/// the fast one (curve_stage.cpp says how, and its bound on the cost).
void exact_maximum(std::vector<CurveFit>& fits, const PointsOf& points_of,
                   const PositionsOf& positions_of, const CurveFitOptions& base, int threads,
                   const WeightsOf& weights_of = {});

}  // namespace sfit::detail
