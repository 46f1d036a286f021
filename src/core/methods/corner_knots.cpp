#include "corner_knots.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "banded_lsq.h"
#include "basis_knots.h"
#include "between_rows.h"
#include "closed_corners.h"
#include "corner_rows.h"
#include "deviation.h"
#include "knot_tensor_lsq.h"
#include "sfit/fold_check.h"
#include "sfit/knot_vector.h"
#include "sfit/parametrization.h"

namespace sfit::detail {
namespace {

constexpr double kRowShare = 0.7;    // the share of T each row alone must hold (step 2)
constexpr double kRidge = 1e-4;      // weight of the second-difference equations
constexpr int kMaxRounds = 60;       // rounds of step 2
constexpr int kMaxSolves = 40;       // tensor solves of steps 3 and 4 together
constexpr double kMaxWork = 3e9;     // flops of all tensor solves together
constexpr double kOnCrease = 1e-12;  // a parameter this close past a corner's U_k is on it

// One direction's knots for a solve: the vector (uniform or not), degree, count.
struct DirectionKnots {
  KnotVector knots;
  int degree = 3;
  int count = 0;
};

// The u knots: a degree-fold knot at each corner, spans[k] uniform spans in stretch k; closed
// (periodic, period 1): a degree-fold knot at 0 too, the seam.
struct CornerBreaks {
  std::vector<double> corners;  // U_1 ... U_K in (0, 1)
  std::vector<int> spans;       // K + 1 stretches
  int degree = 3;
  bool closed = false;
  double edge(std::size_t k) const {
    return k == 0 ? 0.0 : k > corners.size() ? 1.0 : corners[k - 1];
  }
  int count() const {
    int c = degree + (closed ? 0 : 1) + degree * static_cast<int>(corners.size());
    for (int s : spans) c += s - 1;
    return c;
  }
  DirectionKnots knots() const {
    std::vector<double> b{0.0};
    std::vector<int> m;
    if (closed) m.push_back(degree);
    for (std::size_t k = 0; k < spans.size(); ++k) {
      const double a = edge(k), e = edge(k + 1);
      for (int i = 1; i <= spans[k]; ++i) {
        b.push_back(i == spans[k] ? e : a + (e - a) * i / spans[k]);
        if (k + 1 < spans.size() || i < spans[k]) m.push_back(i == spans[k] ? degree : 1);
      }
    }
    return {KnotVector::from_breaks(degree, closed, b, m), degree, count()};
  }
  std::size_t stretch_of(double t) const {
    return static_cast<std::size_t>(std::upper_bound(corners.begin(), corners.end(), t) -
                                    corners.begin());
  }
};

// Each row alone on the u knots (least squares, with the smoothing term): the worst ratio of
// its points to T in each stretch, over every row.
std::vector<double> stretch_worst(const Rows& rows, const std::vector<double>& u,
                                  const Point& centre, const CornerBreaks& cb, const Point& tol) {
  const DirectionKnots d = cb.knots();
  const int p = d.degree, n = d.count, w = p + 1;
  const bool per = cb.closed;
  std::vector<double> worst(cb.spans.size(), 0.0), N(static_cast<std::size_t>(w)), buf;
  std::vector<Point> c;
  const int du = p >= 2 ? 2 : 1;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const auto row = rows[j];
    const double* uj = u.data() + rows.offsets()[j];
    BandedLeastSquares ls(n, w, per);
    for (std::size_t i = 0; i < row.size(); ++i) {
      const int f = eval_basis(d.knots, p, n, per, uj[i], N.data());
      ls.add(f % n, N.data(), row[i] - centre);
    }
    for (int i = 0; i + (per ? 0 : du) < n; ++i) {  // closed: around the wrap too
      const int start = per ? i : std::min(i, std::max(0, n - w));
      buf.assign(static_cast<std::size_t>(w), 0.0);
      const std::size_t o = static_cast<std::size_t>(i - start);
      buf[o] = 1;
      buf[o + 1] = du == 2 ? -2 : -1;
      if (du == 2) buf[o + 2] = 1;
      ls.add(start, buf.data(), Point::Zero(), kRidge);
    }
    if (!ls.solve(c)) {
      std::fill(worst.begin(), worst.end(), 1e300);
      return worst;
    }
    for (std::size_t i = 0; i < row.size(); ++i) {
      const int f = eval_basis(d.knots, p, n, per, uj[i], N.data());
      Point s = Point::Zero();
      for (int a = 0; a <= p; ++a)
        s += N[static_cast<std::size_t>(a)] * c[static_cast<std::size_t>((f + a) % n)];
      const std::size_t k = cb.stretch_of(uj[i]);
      const double miss = max_axis_ratio(s + centre - row[i], tol);
      worst[k] = std::max(worst[k], miss);
      // A row's corner point sits on the crease, which both stretches' control points place:
      // its miss counts for the stretch before it too (else only the one after grows).
      if (k > 0 && uj[i] - cb.corners[k - 1] <= kOnCrease)
        worst[k - 1] = std::max(worst[k - 1], miss);
    }
  }
  return worst;
}

DirectionKnots uniform_v(int degree, int count, double end) {
  const int spans = count - degree;
  std::vector<double> b;
  for (int i = 0; i <= spans; ++i) b.push_back(i == spans ? end : end * i / spans);
  return {KnotVector::from_breaks(degree, false, b), degree, count};
}

// The tensor-product least squares over every point on (du, dv) with the second-difference
// term (knot_tensor_lsq.h), into `s` (data coordinates).
bool solve_tensor(const Rows& rows, const std::vector<double>& u, const std::vector<double>& v,
                  const Point& centre, const DirectionKnots& du, const DirectionKnots& dv,
                  Surface& s) {
  return knot_tensor_lsq(rows, u, v, centre, du.knots, du.degree, du.count, dv.knots, dv.degree,
                         dv.count, kRidge, s);
}

}  // namespace

bool corner_knots_apply(const FitOptions& o) {
  return o.knots == KnotRule::kCorners && o.method == FitMethod::kSurface &&
         o.parametrization == Parametrization::kAuto && !o.counts && !o.closed_v &&
         o.tolerance.minCoeff() > 0;
}

namespace {

// The periodic surface `s` (u knots of `cb`, closed) as the same surface on clamped u knots:
// the seam's degree-fold knot makes it C^0 there, so it is the open surface whose first and
// last control-point columns are both the seam's column (the one basis function that is 1 at
// u = 0). Written so, the CAD formats and viewers read a closed surface with a crease at its
// seam as every other clamped one; the report's "closed" stays true.
Surface clamped(const Surface& s, CornerBreaks cb) {
  const int p = s.degree_u, nu = s.count_u, nv = s.count_v;
  std::vector<double> N(static_cast<std::size_t>(p + 1));
  const int f = eval_basis(s.knots_u, p, nu, true, 0.0, N.data());
  int seam = f;
  for (int a = 0; a <= p; ++a)
    if (N[static_cast<std::size_t>(a)] > N[static_cast<std::size_t>(seam - f)]) seam = f + a;
  cb.closed = false;
  const DirectionKnots d = cb.knots();
  Surface o = s;
  o.periodic_u = false;
  o.count_u = d.count;
  o.knots_u = KnotVector();
  o.set_knots_u(d.knots);
  o.control.resize(static_cast<std::size_t>(d.count) * nv);
  for (int i = 0; i < d.count; ++i)
    for (int j = 0; j < nv; ++j) o.at(i, j) = s.at((seam + i) % nu, j);
  return o;
}

// Steps 1 (parameters) ... 4 and the decision on the matched corners `m` (`closed`: of
// closed rows, with a seam at a common corner).
bool fit_on_corners(const Rows& rows, const MatchedCorners& m, bool closed, int threads,
                    FitResult& r) {
  const Surface& uni = r.surface;  // (replaced at the end: its counts kept for the report)
  const int uni_u = uni.count_u, uni_v = uni.count_v;
  const std::string uni_reason = r.report.stop_reason;
  const Point tol = r.report.tolerance;
  const std::vector<double> u = corner_parameters(rows, m);
  const std::vector<double>& v = r.v;
  const int p = uni.degree_u, q = uni.degree_v;
  const double ev = uni.v_end();
  const long budget = static_cast<long>(uni.count_u) * uni.count_v;
  Point centre = Point::Zero();
  for (const Point& x : rows.points()) centre += x;
  centre /= static_cast<double>(rows.total_points());

  // 2. u spans per stretch, from each row alone.
  CornerBreaks cb;
  cb.corners = m.common;
  cb.degree = p;
  cb.closed = closed;
  cb.spans.assign(m.common.size() + 1, 1);
  while (cb.count() < p + 1) ++cb.spans[0];  // closed: a periodic u needs degree + 1
  for (int round = 0;; ++round) {
    if (round >= kMaxRounds || cb.count() >= uni.count_u) return false;
    const std::vector<double> worst = stretch_worst(rows, u, centre, cb, tol);
    bool any = false;
    for (std::size_t k = 0; k < worst.size(); ++k)
      if (worst[k] > kRowShare) {
        cb.spans[k] += std::max(1, cb.spans[k] / 4);
        any = true;
      }
    if (!any) break;
  }
  // 3. and 4. The tensor solves, bounded in count and work.
  int solves = 0;
  double work = 0;
  Surface s, best;
  auto holds = [&](const CornerBreaks& a, int nv, Surface& out) {
    const double w = p * nv + q + 1;
    work += (double(rows.total_points()) + 2.0 * a.count() * nv) * w * w;
    if (++solves > kMaxSolves || work > kMaxWork) return false;
    if (!solve_tensor(rows, u, v, centre, a.knots(), uniform_v(q, nv, ev), out)) return false;
    return check_deviation(out, rows, u, v, tol, r.report.roundoff, threads).within;
  };
  const int nv_top = std::max(q + 1, static_cast<int>(rows.size()));
  int nv = 0;
  for (int grow = 0; grow < 4 && nv == 0; ++grow) {
    if (static_cast<long>(cb.count()) * (q + 1) >= budget) return false;
    if (holds(cb, nv_top, s)) {
      nv = nv_top;
      best = s;
    } else {
      for (int& sp : cb.spans) sp += std::max(1, sp / 4);
    }
  }
  if (nv == 0) return false;
  for (int lo = q + 1, hi = nv_top; lo < hi;) {  // the fewest nv that holds (bisection)
    const int mid = (lo + hi) / 2;
    if (holds(cb, mid, s)) {
      hi = nv = mid;
      best = s;
    } else {
      lo = mid + 1;
    }
  }
  // Each stretch's spans: one fewer first (the usual case: step 2 was about right), then,
  // where that held, the fewest by bisection (step 2 can overshoot by far: a miss on a crease
  // grows both stretches beside it). A closed u keeps at least degree + 1 control points.
  auto lower_holds = [&](const CornerBreaks& a) { return a.count() >= p + 1 && holds(a, nv, s); };
  for (std::size_t k = 0; k < cb.spans.size(); ++k) {
    CornerBreaks fewer = cb;
    if (cb.spans[k] <= 1 || !lower_holds((--fewer.spans[k], fewer))) continue;
    cb = fewer;
    best = s;
    for (int lo = 1, hi = cb.spans[k]; lo < hi;) {
      fewer.spans[k] = (lo + hi) / 2;
      if (lower_holds(fewer)) {
        hi = fewer.spans[k];
        cb = fewer;
        best = s;
      } else {
        lo = fewer.spans[k] + 1;
      }
    }
  }
  while (nv > q + 1 && holds(cb, nv - 1, s)) {
    --nv;
    best = s;
  }
  // The count, the check, the fold and the calm between rows decide.
  // The count (closed: as written, clamped, the seam's column twice), the check, the fold and
  // the calm between rows decide.
  const BoundingBox box = bounding_box(rows);
  const double fold_limit = kFoldRelative * box.diagonal();
  const RowPairs pairs = row_pairs(rows, false);
  DeviationCheck c;
  ShapeMeasures shape;
  auto fit_for_use = [&](const Surface& f) {
    if (static_cast<long>(f.count_u + (closed ? 1 : 0)) * f.count_v >= budget) return false;
    c = check_deviation(f, rows, u, v, tol, r.report.roundoff, threads);
    if (!c.within) return false;
    shape = measure_shape(f, rows, u, v, box, closed);
    if (fold_measure(f, v) > fold_limit || shape.fold > fold_limit) return false;
    return between_rows_ratio(f, rows, pairs, u, v, tol.maxCoeff()) <= kBetweenRowsLimit;
  };
  if (!fit_for_use(best)) {
    // The fewest nv can fold across fast-changing rows (a bow's stations) where more hold
    // calmly: the fewest nv above it, up to one per row, whose surface is fit for use
    // (bisection, as fold and calm need not be monotone in nv: each pick is checked).
    if (nv >= nv_top || !holds(cb, nv_top, s) || !fit_for_use(s)) return false;
    best = s;
    for (int lo = std::exchange(nv, nv_top) + 1, hi = nv_top; lo < hi;) {
      const int mid = (lo + hi) / 2;
      if (holds(cb, mid, s) && fit_for_use(s)) {
        hi = nv = mid;
        best = s;
      } else {
        lo = mid + 1;
      }
    }
    if (!fit_for_use(best)) return false;  // (c and shape of the surface kept)
  }
  if (closed) best = clamped(best, cb);
  r.surface = std::move(best);
  r.u = u;
  r.v_points.clear();
  r.report.count_u = r.surface.count_u;
  r.report.count_v = r.surface.count_v;
  report_deviation(r.report, c);
  r.report.fold = shape.fold;
  r.report.box_excursion = shape.box_excursion;
  r.report.row_gap = shape.row_gap;
  if (closed) {  // each row starts at its seam corner (aligned_fit.h composes these): the
    // point at or before it and the fraction of the spacing to the next (docs/seams.md)
    r.report.seams.assign(rows.size(), RowSeam{});
    for (std::size_t j = 0; j < rows.size(); ++j) {
      const std::vector<double> f = normalized_positions(rows[j], Parametrization::kChord, true);
      const std::size_t i = static_cast<std::size_t>(
          std::max<long>(0, std::upper_bound(f.begin(), f.end(), m.seam[j]) - f.begin() - 1));
      const double next = i + 1 < f.size() ? f[i + 1] : 1.0;
      r.report.seams[j].shift = static_cast<long>(i);
      r.report.seams[j].offset = next > f[i] ? (m.seam[j] - f[i]) / (next - f[i]) : 0.0;
    }
  }
  // The report's reason: what made the surface (the search's reason was of its own).
  const long kept = static_cast<long>(r.surface.count_u) * r.surface.count_v;
  const long points = static_cast<long>(rows.total_points());
  std::string spans;
  for (int sp : cb.spans) spans += (spans.empty() ? "" : ", ") + std::to_string(sp);
  r.report.stop_reason =
      "corner knots: " + std::to_string(m.common.size()) + " corners matched across the rows" +
      (closed ? " besides the seam's" : "") + ", a crease at each; " + spans +
      " spans between them and " + std::to_string(nv) +
      " control points across, the fewest found that hold T unfolded: " +
      std::to_string(r.surface.count_u) + " x " + std::to_string(r.surface.count_v) + ", " +
      (kept < points ? "below" : "not below") + " the " + std::to_string(points) +
      " points; on uniform knots the method gave " + std::to_string(uni_u) + " x " +
      std::to_string(uni_v);
  // Still above the points: what the method measured of surfaces below them stays said.
  if (kept >= points) r.report.stop_reason += " (" + uni_reason + ")";
  r.report.method = FitMethod::kSurface;
  r.report.knots = KnotRule::kCorners;
  r.report.parametrization = Parametrization::kChord;
  return true;
}

// Corners found and matched (closed rows: with a seam at a common corner, closed_corners.h),
// `between`: closed rows' corners between points; then fit_on_corners(). Corners followed from
// row to row beyond the mean's reach (a bow's) can fold the surface where the mean's own (the
// rest interpolated) do not: then those are tried.
bool corner_knots_at(const Rows& rows, int threads, bool between, FitResult& r) {
  const Surface& uni = r.surface;
  const Point tol = r.report.tolerance;
  if (uni.periodic_v || !r.report.within_tolerance || !(tol.minCoeff() > 0) || rows.size() < 2 ||
      r.v.size() != rows.size())
    return false;
  const bool closed = uni.periodic_u;
  std::vector<std::vector<RowCorner>> found(rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j)
    found[j] = row_corners(rows[j], tol, closed, between);
  const MatchedCorners m = closed ? match_closed_corners(rows, found) : match_corners(found);
  if (m.empty()) return false;
  if (fit_on_corners(rows, m, closed, threads, r)) return true;
  if (closed || !m.followed) return false;
  const MatchedCorners near = match_corners(found, false);
  return !near.empty() && fit_on_corners(rows, near, false, threads, r);
}

}  // namespace

bool corner_knots(const Rows& rows, const FitOptions& /*options*/, int threads, FitResult& r) {
  if (!r.surface.periodic_u) return corner_knots_at(rows, threads, false, r);
  // (Both attempts start from the search's periodic surface; the kept one comes out clamped.)
  // Closed rows: the corners at their points, and between points where the lines either side
  // meet (a sharp corner between samples); the smaller surface.
  FitResult at = r, between = r;
  const bool a = corner_knots_at(rows, threads, false, at);
  const bool b = corner_knots_at(rows, threads, true, between);
  const auto count = [](const FitResult& x) { return long(x.surface.count_u) * x.surface.count_v; };
  if (b && (!a || count(between) < count(at)))
    r = std::move(between);
  else if (a)
    r = std::move(at);
  return a || b;
}

}  // namespace sfit::detail
