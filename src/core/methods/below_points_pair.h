// One pair nu x nv of the fallback below the points (docs/method.md 7.12, below_points.h):
// solved from the base surface's fractions with the calm term, its parameters corrected by
// projection, judged at every point, by the geometric rule's guard and for a fold; and the
// work it costs, charged to the fallback's budget. Private to the surface method.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "below_points.h"
#include "geometric_params.h"
#include "geometric_search.h"
#include "scattered_lsq.h"
#include "search_frame.h"

namespace sfit::detail {

/// Flops charged for one pass over a point (the data term's sums, a judgement, a projection).
inline constexpr double kPointWork = 2e3;

/// The fallback's work, in flops: each solve is charged its factorisation
/// (ScatteredProblem::cost(), twice where the height alone is calmed) and one pass over the
/// points, each projection of the parameters one more pass. Where it is over, no new pair is
/// tried.
struct Budget {
  double limit = 0, spent = 0;
  bool over() const { return spent >= limit; }
};

/// A pair tried.
struct Tried {
  bool holds = false;  // T at every point, the guard and no fold
  double ratio = HUGE_VAL;
  Surface s;
  double smoothing = 0;
  std::vector<double> fu, fv;  // the points' fractions the surface was made at
  int corrections = 0;
};

/// One pair: from the base surface's fractions (fu0, fv0), corrected by projection onto the fit
/// (as the geometric search does) while the worst deviation falls and T is missed by at most
/// 3x; then the rule's guard (stays_near_where_covered()) and no fold. Where T held only at the
/// lowest smoothness and a guard failed, the weights in between, calmer first (one that is calm
/// and unfolded but misses T by at most kSmoothingReach gets one more correction round at that
/// weight). `normal`: an open sheet's height direction, calmed alone first.
/// `plane` > 0 (relative, as the smoothness): the coordinates in the base plane (all but the
/// height along `normal`) are solved with at least this smoothness (the warped pass of
/// fit_below_points(): its columns must stay straight in the plane); 0: as the search.
/// `calmer` (the stretched pass, below_points_dense.h): where T held but a guard failed after
/// the weights above, calmer weights than the search's too (10, 100, 1000 times), each
/// corrected by projection at that weight while it passes the guards and misses T by at most
/// 2x.
Tried attempt(const Frame& fr, const ScatteredSpec& spec, const std::vector<double>& fu0,
              const std::vector<double>& fv0, int nu, int nv, const std::optional<Point>& normal,
              Budget& budget, double plane = 0, bool calmer = false);

/// What every pair below the points is solved from: the base surface's fractions (u warped by
/// warp_by_chord() where `warp`), the spec and an open sheet's height direction (the normal of
/// the points' best plane; closed rows have none). nullopt where there is no base surface.
struct Setup {
  Fractions f;
  ScatteredSpec spec;
  std::optional<Point> normal;
};
std::optional<Setup> prepare(const Frame& fr, const FitOptions& o, bool warp);

/// An open sheet's u warped by each row's own chord length (docs/method.md 7.12): each point's
/// u (the base plane's) moved halfway to where the row's chord length (in 3D, so a roof's or a
/// tree's step lengthens it) puts it between the row's first and last u. Parameter range then
/// goes where the height changes along the row, as the row rules' chord length does, while the
/// row keeps its place in the plane (the columns zigzag half as far as under the row rules).
void warp_by_chord(const Rows& rows, std::vector<double>& fu);

}  // namespace sfit::detail
