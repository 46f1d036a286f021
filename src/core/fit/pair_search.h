// The search over pairs of counts (nu, nv) for the fewest nu x nv that hold, separated from
// the solver that says whether a pair holds (docs/control-points.md). Private.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <utility>

namespace sfit::detail {

/// What a solver says about one pair.
struct PairVerdict {
  bool holds = false;
  /// Worst |S - D| / T over the points and axes (infinite where no surface was made).
  double ratio = 0;
};

/// A memo of verdicts around a solver: each pair is solved once.
class PairOracle {
 public:
  explicit PairOracle(std::function<PairVerdict(int, int)> solve) : solve_(std::move(solve)) {}
  const PairVerdict& operator()(int nu, int nv);
  bool known(int nu, int nv) const { return memo_.count({nu, nv}) > 0; }
  const PairVerdict* find(int nu, int nv) const {
    auto it = memo_.find({nu, nv});
    return it == memo_.end() ? nullptr : &it->second;
  }
  long tried() const { return static_cast<long>(memo_.size()); }
  /// Every pair solved so far and its verdict.
  const std::map<std::pair<int, int>, PairVerdict>& verdicts() const { return memo_; }

 private:
  std::function<PairVerdict(int, int)> solve_;
  std::map<std::pair<int, int>, PairVerdict> memo_;
};

struct PairRange {
  int min_u, max_u, min_v, max_v;
  /// Whether a pair is worth solving at all (its cost within the search's budget); empty:
  /// every pair. Must be monotone: a pair with fewer control points along u is affordable
  /// where one with more is. The search caps each column's nu at the largest affordable one.
  std::function<bool(int, int)> affordable = {};
  /// How many fewer along u or v the last descent (descend()) tries where one fewer fails:
  /// 1, or 2 where holding is not quite monotone in a count (a pair can fail between two
  /// that hold) and the result's minimality is judged by the same oracle.
  int reach = 1;
};

struct PairChoice {
  int nu = 0, nv = 0;  ///< 0: no pair below `bound` held
  std::string stop;    ///< why the search stopped there
};

/// The pair with the fewest nu x nv < bound that holds (the first found on a tie).
/// Assumes holding is close to monotone in each count (more control points do not hold
/// worse); where it is not, the result is still a pair that holds, and the last step, a
/// descent to (nu - 1, nv) or (nu, nv - 1) while either holds, leaves a pair where one fewer
/// in either direction fails (stop "minimal").
/// For nv along a geometric sequence, and then every nv between two of them whose bound on the
/// product can still beat the best, the smallest nu that holds (bisection below the previous
/// nv's, and below bound / nv). A column is skipped where even the exact smallest nu of a
/// larger nv times this nv cannot beat the best; it starts at the largest affordable nu
/// (PairRange::affordable), and steps down from a top pair that holds T at every point but
/// fails a guard (factor 0.8) until one holds or misses T at the points.
PairChoice search_pairs(const PairRange& range, long bound, PairOracle& holds);

/// From a pair that holds under `oracle`, steps to (nu - 1, nv) or (nu, nv - 1) while either
/// holds, else (range.reach = 2) to (nu - 2, nv) or (nu, nv - 2) (only pairs `worth_trying`
/// are asked). Returns the pair reached: one fewer in either direction fails there.
std::pair<int, int> descend(int nu, int nv, const PairRange& range, PairOracle& oracle,
                            const std::function<bool(int, int)>& worth_trying = {});

/// The stop reason of a search made on every `step`-th point of each row and verified on all
/// of them ("every 2nd point", "every 20th point").
std::string minimal_on_sample(int step);

}  // namespace sfit::detail
