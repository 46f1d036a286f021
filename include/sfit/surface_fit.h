// Rows of points to one B-spline surface within a per-axis tolerance (docs/method.md sections 3-5),
// with every data point checked on the finished surface.
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sfit/curve_fit.h"
#include "sfit/fit_limits.h"
#include "sfit/parametrization.h"
#include "sfit/progress.h"
#include "sfit/rows.h"
#include "sfit/seam_alignment.h"
#include "sfit/surface.h"

namespace sfit {

/// Deviations below this fraction of the data's size count as round-off (used at T = 0).
inline constexpr double kRoundoffRelative = 1e-10;

/// How the control-point counts are found (docs/control-points.md): the built-in methods; a
/// method registered at run time has an id beyond these (docs/method.md 7.11), which
/// to_string() and parse_fit_method() know while it is registered.
enum class FitMethod {
  /// Default: tensor-product least squares over all points at once at each pair (nu, nv),
  /// checked at the full T per axis, and a search for the fewest nu x nv that hold; starts
  /// from what kSfit01 finds, so it never gives more control points than kSfit01.
  kSurface,
  /// The paper's two stages (curve stage on the rows, transverse stage on the columns, each
  /// within T/2; docs/method.md), bit for bit as before the surface search existed.
  kSfit01,
};
/// The norm the surface search fits with at a pair (nu, nv).
enum class FitNorm {
  kL2,    ///< least squares
  kLinf,  ///< minimax: the smallest max |S - D| per axis at that pair (a linear program)
  kAuto,  ///< least squares, and minimax where least squares misses T by a little
};
/// Where the knots go (docs/method.md, "Adaptive knots").
enum class KnotRule {
  kUniform,   ///< uniform knots (the paper's)
  kAdaptive,  ///< also a fit on knots placed where the residuals concentrate, kept when smaller
  /// The default: uniform knots, and beside them, where the rows have corners matched across
  /// them, a degree-fold knot at each corner and uniform knots between, kept when smaller
  /// (docs/method.md 7.13). kUniform asks for uniform knots alone; kAdaptive, as before corner
  /// knots, for uniform and adaptive knots (no corner knots).
  kCorners,
};
/// "surface", "sfit01"; "l2", "linf", "auto"; "uniform", "adaptive", "corners".
std::string_view to_string(FitMethod m);
std::string_view to_string(FitNorm n);
std::string_view to_string(KnotRule k);
/// The inverses of to_string(); false if `name` is none of them.
bool parse_fit_method(std::string_view name, FitMethod& out);
bool parse_fit_norm(std::string_view name, FitNorm& out);
bool parse_knot_rule(std::string_view name, KnotRule& out);

struct FitOptions {
  int degree_u = 3;                 ///< degree along the rows, 1 ... 20
  int degree_v = 3;                 ///< degree across the rows, 1 ... 20
  Point tolerance = Point::Zero();  ///< T = (Tx, Ty, Tz) >= 0, absolute; 0 interpolates
  bool closed_u = false;            ///< rows are closed contours (first point not repeated)
  bool closed_v = false;            ///< the sequence of rows is closed
  CountSearch search = CountSearch::kFast;
  /// How points get their parameters, in both directions (docs/method.md 3 and 7.4). Across the
  /// rows, the geometric rules average the columns' normalized chord lengths (one v per row,
  /// shared by every column, as the guarantee needs).
  /// kAuto: the paper's for kSfit01, each of the four rules for kSurface (as kFewest).
  Parametrization parametrization = Parametrization::kAuto;
  /// kAdaptive: beside the uniform fit, one on knots where the shape needs them (open
  /// directions, one v per row), kept only when it has strictly fewer control points, holds T
  /// at every point and does not fold; so it never raises the count. kCorners (the default):
  /// the corner knots beside the uniform fit where the rows have corners; kUniform: neither.
  KnotRule knots = KnotRule::kCorners;
  /// Counts to start the searches from, e.g. a previous fit's report.row_counts and
  /// column_counts (used where their size matches the rows, the columns); kKnown takes them
  /// as the answer. Without them kFast starts each row from the previous row's count, in
  /// fixed blocks of 16 rows (so the result does not depend on the thread count).
  std::vector<int> row_count_hints, column_count_hints;
  int threads = 0;  ///< 0: all cores; results are identical for any count
  FitMethod method = FitMethod::kSurface;
  FitNorm norm = FitNorm::kAuto;  ///< kSurface only (kSfit01 is least squares)
  /// kSurface only: fit at exactly these counts (nu, nv), no search; the report says whether
  /// the surface holds T (a fast refit, e.g. while an editor drags a point).
  std::optional<std::array<int, 2>> counts;
  // Seams and orientation (docs/seams.md). Both keep: the rows are fitted exactly as given.
  SeamMode seam = SeamMode::kAlign;       ///< closed rows: start where the neighbour starts
  OrientMode orient = OrientMode::kAuto;  ///< rows running against their neighbour are reversed
  /// Where the re-representation samples each row curve (docs/seams.md): the paper's
  /// parameters, or equal arc length (open rows at the paper's parameters).
  Resampling rerepresentation = Resampling::kPaper;
  /// A surface that folds between rows (fold_check.h) is refitted with another rule across
  /// the rows. false, with seam and orient kKeep: the paper's scheme exactly.
  bool fold_guard = true;
  /// Progress of the fit (sfit/progress.h): phase, pairs tried, best so far, time; false
  /// stops the fit (Error kCancelled). Never changes a result.
  ProgressFunction progress;
  /// When set and true, the fit stops (Error kCancelled) at its next check, on any thread,
  /// within about kProgressInterval of work; may be set from a signal handler.
  const std::atomic<bool>* cancel = nullptr;
};

/// What a fit achieved (docs/surface-json.md, "The report").
struct FitReport {
  std::size_t points = 0;
  std::size_t rows = 0;
  Point tolerance = Point::Zero();
  Point max_deviation = Point::Zero();  ///< per axis, over every data point, on the surface
  long worst_row = -1;                  ///< the point using most of its tolerance
  long worst_index = -1;
  Point worst_deviation = Point::Zero();  ///< surface minus data there, signed
  bool within_tolerance = false;
  int count_u = 0;  ///< nu (distinct control points along u)
  int count_v = 0;  ///< nv
  int degree_u = 0, degree_v = 0;
  bool closed_u = false, closed_v = false;
  Parametrization parametrization = Parametrization::kPaper;  ///< the rule that made it
  /// Minimal count of each row (curve stage); for kSurface those of the kSfit01 fit it
  /// started from (column_counts, raised_*, repaired_* likewise).
  std::vector<int> row_counts;
  std::vector<int> column_counts;  ///< minimal count of each column (transverse stage)
  int raised_u = 0;                ///< times nu was raised above max(row_counts) by the guarantee
  int raised_v = 0;                ///< times nv was raised above max(column_counts)
  int repaired_rows = 0;           ///< rows whose paper re-representation needed the repair
  int repaired_columns = 0;
  int tightenings = 0;  ///< times both stage budgets were halved after a failed final check
  long solves = 0;      ///< least-squares solves made by the count searches
  double roundoff = 0;  ///< absolute round-off allowance used at T = 0
  double seconds = 0;
  FitMethod method = FitMethod::kSfit01;  ///< the method that made the surface
  FitNorm norm = FitNorm::kL2;            ///< the norm that made it (kL2 or kLinf)
  long pairs_tried = 0;                   ///< (nu, nv) pairs the surface search solved at
  /// Why the surface search stopped where it did (empty for kSfit01), e.g. "minimal": at the
  /// chosen pair one fewer in either direction fails; "sfit01": nothing smaller held.
  std::string stop_reason;
  // Seams and shape measures (docs/seams.md).
  std::vector<RowSeam> seams;  ///< each row's start and direction as fitted; empty: as given
  /// The rule across the rows: `parametrization`, or the one the fold guard chose.
  Parametrization parametrization_across = Parametrization::kPaper;
  double box_excursion = 0;  ///< largest distance of the sampled surface outside the data's box
  double fold = 0;           ///< how far the surface doubles back between rows (fold_check.h)
  double row_gap = 0;        ///< largest distance, sampled between rows, to the nearer data row
  /// The knots that made the surface: kAdaptive where `--knots adaptive` found a smaller
  /// surface on its own knots (kept), kCorners where the corner knots did (then
  /// `parametrization` is kChord: chord lengths remapped to the corners), else kUniform.
  KnotRule knots = KnotRule::kUniform;
  /// kSurface: the rules the search looked at, in order: their pairs tried, or none where the
  /// rows fitted alone at T need more control points than the search could win with (empty: no
  /// search, e.g. T = 0).
  std::vector<Parametrization> rules_searched;
};

struct FitResult {
  Surface surface;
  FitReport report;
  std::vector<double> u;  ///< parameter u of every data point, in the order of Rows::points()
  /// Parameter v of every row. Parametrization::kGeometric: each row's mean v_points (its
  /// points' v differ), for what reads one v per row (a row's label, not where it is fitted).
  std::vector<double> v;
  /// Parameter v of every data point (order of Rows::points()) where the rule gives each point
  /// its own (Parametrization::kGeometric); empty for the row rules (point k of row j is at
  /// v[j]). Evaluate at point_v().
  std::vector<double> v_points;
  /// The v the surface was fitted at for the point of row `row` whose index in
  /// Rows::points() is `index`.
  double point_v(std::size_t row, std::size_t index) const {
    return v_points.empty() ? v[row] : v_points[index];
  }
  /// v as the checks take it: v_points where set, else v (one per row).
  const std::vector<double>& v_for_points() const { return v_points.empty() ? v : v_points; }
};

/// Checks rows and options; throws Error (kInputData for the data, kUsage for the options)
/// naming the row/point or option and the offending values.
void validate(const Rows& rows, const FitOptions& options);

/// T = fraction x the bounding-box diagonal on every axis (the default fraction of every
/// front end is kDefaultToleranceFraction, sfit/fit_limits.h).
Point relative_tolerance(const Rows& rows, double fraction);

/// Validates once, aligns seams, centres, runs the method options.method (from the method
/// registry), checks the surface as written at every point for every method (one criterion)
/// and adapts the knots where asked (docs/method.md 7.11). kSurface (default,
/// docs/control-points.md): the kSfit01 fit below gives a pair that holds; then, for each parameter
/// rule, the tensor-product fit over all points at once is searched for the fewest nu x nv that
/// hold T per axis at every point (checked on the finished surface, as below, and guarded against
/// swings between points); the smallest wins, the kSfit01 surface where nothing smaller holds.
///
/// kSfit01, the paper's method: curve stage on each row (minimal count within T/2),
/// re-representation on the common count nu, transverse stage on the nu columns of control points
/// (minimal count within T/2), re-representation on nv, assembly, and the check of every data
/// point.
///
/// The guarantee: each re-representation is checked point by point and repaired
/// (rerepresent()); where that cannot hold a row (column), nu (nv) is raised. Columns are
/// re-represented at one common v per row, so by the partition of unity every point is within
/// T/2 + T/2 = T. The final check confirms it; if round-off defeats it, both stage budgets are
/// halved and the fit redone (at most 3 times). report.within_tolerance is false only if all
/// of that failed. Fitting runs on coordinates centred on the bounding box, so an offset of
/// the data costs no digits. Throws Error as validate() does.
FitResult fit_surface(const Rows& rows, const FitOptions& options);

}  // namespace sfit
