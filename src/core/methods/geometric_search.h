// The surface search at Parametrization::kGeometric (docs/method.md 7.9): the fewest nu x nv
// whose scattered least-squares fit (scattered_lsq.h) holds T at every point, with the
// points' parameters from a base surface (geometric_params.h), corrected by projection while
// that lowers the count. Private to the surface method.
#pragma once

#include <climits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geometric_params.h"
#include "scattered_lsq.h"
#include "search_frame.h"

namespace sfit::detail {

/// Rounds of parameter correction (each: project, refit, descend) while the count falls.
inline constexpr int kCorrectionRounds = 3;

/// Gauss-Newton steps per point and round of parameter correction (project_parameters()).
inline constexpr int kNewtonSteps = 3;

/// Where a pair misses T by at most this factor, the smoothness weight is lowered (by
/// kSmoothingLower) and the pair refitted once: the term may be what misses. The lower weight
/// still decides the spans without data (as any positive weight does) but pulls far less.
inline constexpr double kSmoothingReach = 1.25;
inline constexpr double kSmoothingLower = 1e-4;

/// A surface of the rule (centred) with its points' parameters at its counts.
struct GeometricFit {
  Surface surface;
  std::vector<double> u, v;     ///< per point, rows.points() order
  std::string stop;             ///< why the search stopped there
  long tried = 0;               ///< pairs solved
  int corrections = 0;          ///< rounds of parameter correction that lowered the count
  double smoothing = 0;         ///< the smoothness weight the surface was made with
  FitNorm norm = FitNorm::kL2;  ///< kLinf: minimax at the rule's parameters (no pair held by l2)
};

/// The most unknowns (nu x nv) a pair of the search may have: larger pairs are not tried (their
/// factorisation costs too much), so a rule whose floor is above it cannot find one.
inline constexpr long kGeometricMaxUnknowns = 20000;

/// Coarse to fine: on large data the pairs are searched on every step-th point of each row
/// (search_pairs(), below `bound` and below the points' number), the parameters corrected there
/// (project_parameters(), refit, descend: rounds while the count falls), then the pair is
/// verified on every point (raised until it holds, descended while one fewer holds). A pair
/// holds when the frame's judge passes it (every point within T, the guards) and the surface
/// does not fold. nullopt: no base surface, or nothing below `bound` held.
/// `corrections`: the most rounds of parameter correction (tests compare 0 with the default).
/// `pairs`: set to the pairs solved, whether or not a surface is found.
/// On an open sheet, where the best plane's parameters gave a surface, the search runs again
/// over its coordinate plane's (BasePlane::kAxis, geometric_params.h) below that count; the
/// fewer control points are kept (a tie: the best plane's).
/// Where no pair held by least squares, minimax is tried at the nearest pairs below
/// `linf_bound` too (FitNorm::kAuto and kLinf; geometric_minimax.h). The default passes 0
/// where a row rule found a pair (an LP of a few hundred unknowns on 2 x 10^4 points can take a
/// minute: uneven_rows of bench/scan_cases.py at 1e-3), else its bound.
/// Then, over the best plane, below the count found (or `bound`), the search with the
/// reweighted fit at near misses (search_geometric_counted(), `reweighted`; no minimax), where the
/// plain searches missed by at most kReweightReach at fewer control points than they found and
/// the reweighted fit held at one of the best plane's near misses (tried there on a copy: where
/// none held, the reweighted search would solve the plain one's pairs and end at its count);
/// kept where it has fewer.
std::optional<GeometricFit> search_geometric(const Frame& fr, const FitOptions& o, long bound,
                                             int corrections = kCorrectionRounds,
                                             long* pairs = nullptr, long linf_bound = LONG_MAX);
/// search_geometric() over one base plane (`plane`), adding the pairs solved to `tried` as it
/// goes. `reweighted`: a pair whose least-squares fit misses T by at most kReweightReach is
/// fitted again by reweighted least squares (geometric_reweight.h) and holds where that does.
/// `near_miss`: lowered to the control points of every pair solved that missed T (or its
/// guards) by at most kReweightReach.
/// `reweight_held` (not `reweighted`): at each pair the reweighted search would reweight, the
/// reweighted fit is tried on a copy (the search itself stays least squares) until one holds,
/// which sets *reweight_held: up to there the reweighted search solves the same pairs.
/// `smoothing`: the smoothness weight every pair starts at (attempt() lowers it from there).
/// `lower_helps` (at the default weight): where no pair held, set to whether the largest pair
/// of the diagonal holds, or misses by at most 3/4 as much, with the weight lowered.
std::optional<GeometricFit> search_geometric_counted(
    const Frame& fr, const FitOptions& o, long bound, int corrections, long& tried,
    BasePlane plane = BasePlane::kBest, long linf_bound = LONG_MAX, bool reweighted = false,
    long* near_miss = nullptr, bool* reweight_held = nullptr, double smoothing = kSmoothing,
    bool* lower_helps = nullptr);

/// The rule's surface at exactly (nu, nv) (FitOptions::counts), holding or not; nullopt where
/// the rule has no base surface for the rows. The smoothness weight starts at `smoothing`
/// (relative, scattered_lsq.h) and is lowered while the surface misses T (GeometricFit::
/// smoothing says which it was made with).
/// `plane`: the base plane of an open sheet (geometric_params.h). `reweighted`: as in
/// search_geometric_counted() (the search's pair may have held only reweighted).
std::optional<GeometricFit> geometric_at_counts(const Frame& fr, const FitOptions& o, int nu,
                                                int nv, double smoothing = kSmoothing,
                                                BasePlane plane = BasePlane::kBest,
                                                bool reweighted = true);

/// The result of a surface of the rule: assemble() with the shape measured on the surface
/// (the fold on columns sampled evenly across the domain; the rows are no iso-curves, so
/// row_gap is 0) and v_points set (v: each row's mean v).
FitResult assemble_geometric(const Frame& fr, GeometricFit g, const DeviationCheck& c,
                             const FitOptions& o);

/// The knot spans (cells, u-major: a * spans_v + b) that hold a data point at parameters u, v
/// (per point at s's counts).
std::vector<char> covered_spans(const Surface& s, std::span<const double> u,
                                std::span<const double> v);

/// The rule's guard (in place of fit_frame.h's): every control point within the data's box
/// grown by its diagonal; the surface, sampled 4 times per span each way, within the box
/// grown by 1/10 of the diagonal in the spans that hold data or lie between two that do in
/// their column or row (holes, gaps between rows), and by 1/2 (calm) in the spans outside
/// (clipped corners, outside an outline), where the smoothness term alone decides it.
bool stays_near_where_covered(const Surface& s, std::span<const double> u,
                              std::span<const double> v, const BoundingBox& box);

/// Fractions of the domain of parameters u, v at s's counts (a closed direction's end wrapped
/// to 0): what a round of correction gives the next problem.
void to_fractions(const Surface& s, const std::vector<double>& u, const std::vector<double>& v,
                  std::vector<double>& fu, std::vector<double>& fv);

/// The fold of a surface over evenly spaced columns (fold_measure()).
double geometric_fold(const Surface& s);

/// A verdict of judge_with_guards(): `verdict` is the frame's judge's (its ratio: the worst
/// |S - D| / T), holding only where the guards passed too; `folded`: every point within T and
/// near the data, but the surface folds.
struct GuardedVerdict {
  PairVerdict verdict;
  bool folded = false;
};

/// Whether a surface of the rule holds with its guards, cheapest first and each only where
/// the one before passed: every point within T (Frame::judge() with its own guards off, `out`
/// and `sample` as there), the surface near the data where the data is
/// (stays_near_where_covered()), no fold (geometric_fold() at most kFoldRelative of the
/// box's diagonal), and, judged on every point (no `sample`), calm between the rows
/// (between_rows_ratio() at most kBetweenRowsLimit). The one check of the rule's search, its
/// reweighting and its minimax.
GuardedVerdict judge_with_guards(const Frame& fr, const Surface& s, std::span<const double> u,
                                 std::span<const double> v, DeviationCheck* out = nullptr,
                                 const Rows* sample = nullptr);

}  // namespace sfit::detail
