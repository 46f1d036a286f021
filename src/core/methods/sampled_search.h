// The surface search's coarse-to-fine step (surface_method.cpp) and the budget of its solves.
// Private.
#pragma once

#include <cstddef>
#include <span>

#include "few_rows.h"
#include "pair_search.h"
#include "search_frame.h"
#include "tensor_lsq.h"

namespace sfit::detail {

/// Above this many points the search runs on every step-th point of each row (the positions
/// those points have in the full rows), and its pair is then verified on all points: raised
/// until it holds there, and descended to where one fewer either way fails on all points.
/// The choice is then as minimal as on the full data wherever holding is monotone near it.
/// 5e4 rather than 1e5: the peer benchmark's 10^5-point grid and ragged sets keep their counts
/// and take 0.2-0.5 s instead of 0.3-0.9 s (the 10^6-point grid at 1e-3 gets 14 x 11 instead
/// of 11 x 12; docs/control-points.md).
inline constexpr std::size_t kSearchPoints = 50000;

/// The most flops a pair's solve may cost on a problem of `points` points: pairs beyond it are
/// not tried (they count as not holding; the report says how many).
double solve_budget(std::size_t points);

/// One rule's search on large data: the pairs below `bound` searched on every `step`-th point
/// of each row of the frame's rows (`prob`: the rule's problem on all of them), the pair found
/// there raised until it holds on all points (`on_all`, over `range`), then descended while
/// one fewer holds there. nu = 0 where none holds. `tried` grows by the sample's solves.
PairChoice search_on_sample(const Frame& fr, const FewRows& few, const TensorProblem& prob,
                            const TensorSpec& spec, const Point& tolerance, std::size_t step,
                            const PairRange& range, long bound, PairOracle& on_all, long& tried);

}  // namespace sfit::detail
