#include "sfit/surface_fit.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "parallel.h"
#include "sfit/basis.h"
#include "sfit/deviation.h"
#include "sfit/error.h"
#include "sfit/parametrization.h"
#include "sfit/rerepresent.h"

namespace sfit {
namespace {

std::string format_point(const Point& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return buf;
}

}  // namespace

void validate(const Rows& rows, const FitOptions& o) {
  auto check_degree = [](int d, const char* name) {
    if (d < 1 || d > kMaxDegree)
      throw Error(ErrorCode::kUsage,
                  std::string(name) + " (" + std::to_string(d) + ") must be 1 ... " +
                      std::to_string(kMaxDegree),
                  Place{.option = name}, {static_cast<double>(d)});
  };
  check_degree(o.degree_u, "degree_u");
  check_degree(o.degree_v, "degree_v");
  if (o.threads < 0)
    throw Error(ErrorCode::kUsage, "threads must be >= 0", Place{.option = "threads"},
                {static_cast<double>(o.threads)});
  const std::size_t M = rows.size();
  if (M == 0) throw Error(ErrorCode::kInputData, "no points: the input has no rows");
  if (M < 2)
    throw Error(ErrorCode::kInputData,
                "one row makes a curve, not a surface: a surface needs at least 2 rows",
                Place{.row = 0}, {static_cast<double>(M)});
  if (o.closed_v && M < 3)
    throw Error(ErrorCode::kInputData,
                "a closed sequence of rows needs at least 3 rows, got " + std::to_string(M),
                Place{}, {static_cast<double>(M)});
  for (std::size_t j = 0; j < M; ++j) {
    const auto row = rows[j];
    const long jl = static_cast<long>(j);
    if (row.empty()) throw Error(ErrorCode::kInputData, "row has no points", Place{.row = jl});
    if (o.closed_u && row.size() == 2)
      throw Error(ErrorCode::kInputData,
                  "a closed row needs at least 3 points (or 1 for a pole), got 2", Place{.row = jl},
                  {2.0});
    for (std::size_t k = 0; k < row.size(); ++k)
      if (!row[k].allFinite())
        throw Error(ErrorCode::kInputData, "coordinate is not a finite number",
                    Place{.row = jl, .point = static_cast<long>(k)},
                    {row[k].x(), row[k].y(), row[k].z()});
  }
  // The data must span a surface: not one point, not one straight line; and its size must
  // leave room for squares in double precision (1e-150 ... 1e150; an offset costs nothing).
  const BoundingBox box = bounding_box(rows);
  const Point& p0 = rows.points().front();
  if ((box.max - box.min).maxCoeff() == 0)
    throw Error(ErrorCode::kInputData,
                "all " + std::to_string(rows.total_points()) + " points coincide at " +
                    format_point(p0) + ": they span no surface",
                Place{}, {p0.x(), p0.y(), p0.z()});
  const double size = box.diagonal();
  if (!(size >= 1e-150 && size <= 1e150))
    throw Error(ErrorCode::kInputData,
                "the data's size is out of the range sfit computes in (1e-150 ... 1e150): "
                "coordinates span " +
                    format_point(box.min) + " ... " + format_point(box.max),
                Place{}, {size});
  const Point* far = &p0;
  for (const Point& p : rows.points())
    if ((p - p0).squaredNorm() > (*far - p0).squaredNorm()) far = &p;
  const Point dir = (*far - p0).normalized();
  double off_line = 0;
  for (const Point& p : rows.points())
    off_line = std::max(off_line, ((p - p0) - (p - p0).dot(dir) * dir).norm());
  if (off_line <= kRoundoffRelative * size)
    throw Error(ErrorCode::kInputData,
                "all points lie on one straight line through " + format_point(p0) + " and " +
                    format_point(*far) + ": they span no surface",
                Place{}, {off_line});
  // Checked after the data, as a tolerance relative to an overflowing extent is infinite.
  for (int a = 0; a < 3; ++a) {
    const double t = o.tolerance[a];
    if (!(t >= 0.0) || !std::isfinite(t))
      throw Error(ErrorCode::kUsage,
                  std::string("tolerance ") + "xyz"[a] + " must be a finite number >= 0",
                  Place{.option = "tolerance"}, {t});
  }
}

Point relative_tolerance(const Rows& rows, double fraction) {
  return Point::Constant(fraction * bounding_box(rows).diagonal());
}

namespace {

struct Attempt {
  Surface surface;  // centred coordinates
  std::vector<double> u, v;
  FitReport report;
};

// Fits `curves` points each with fit_curve, then re-represents all on one common count,
// raising it until every curve holds its points (the guarantee's first half).
struct StageResult {
  std::vector<Rerepresentation> curves;
  std::vector<int> counts;
  int raised = 0;
  int repaired = 0;
  long solves = 0;
  int common = 0;
  std::vector<double> shared_parameters;  // set when all curves share parameters (columns)
};

template <class GetPoints>
StageResult run_stage(std::size_t n_curves, GetPoints&& points_of, int degree, bool periodic,
                      const Point& bound, CountSearch search, int threads, bool shared_params,
                      std::size_t max_points, const std::vector<int>& hints) {
  StageResult st;
  std::vector<CurveFit> fits(n_curves);
  // Fixed blocks of consecutive curves, each block in order: a curve's search starts from
  // its predecessor's count (neighbouring rows need similar counts). The blocks do not
  // depend on the thread count, so neither do the results.
  constexpr std::size_t kBlock = 16;
  const bool have_hints = hints.size() == n_curves;
  const std::size_t n_blocks = (n_curves + kBlock - 1) / kBlock;
  detail::parallel_for(n_blocks, threads, [&](std::size_t b) {
    int previous = 0;
    for (std::size_t i = b * kBlock; i < std::min(n_curves, (b + 1) * kBlock); ++i) {
      CurveFitOptions co{degree, periodic, bound, search, have_hints ? hints[i] : previous};
      fits[i] = fit_curve(points_of(i), co);
      previous = fits[i].curve.degree == degree ? fits[i].curve.count() : previous;
    }
  });
  st.counts.resize(n_curves);
  int common = degree + 1;
  for (std::size_t i = 0; i < n_curves; ++i) {
    st.counts[i] = fits[i].curve.count();
    st.solves += fits[i].solves;
    common = std::max(common, st.counts[i]);
  }
  const int first_common = common;
  const int cap = static_cast<int>(std::max<std::size_t>(max_points, common)) + degree + 8;
  st.curves.resize(n_curves);
  while (true) {
    if (shared_params)
      st.shared_parameters =
          paper_parameters(degree, common, periodic, static_cast<int>(max_points));
    // Stop the pass at the first curve that fails: the count is raised whatever the others
    // do, so the outcome (the first count at which every curve holds) is the same.
    std::atomic<bool> failed{false};
    detail::parallel_for(n_curves, threads, [&](std::size_t i) {
      if (failed.load(std::memory_order_relaxed)) return;
      st.curves[i] = rerepresent(fits[i], points_of(i), degree, common, periodic, bound,
                                 shared_params ? std::span<const double>(st.shared_parameters)
                                               : std::span<const double>());
      if (!st.curves[i].holds) failed.store(true, std::memory_order_relaxed);
    });
    if (!failed.load()) break;
    if (common >= cap)
      throw Error(ErrorCode::kToleranceNotMet,
                  "re-representation cannot hold the tolerance even with " +
                      std::to_string(common) + " control points",
                  Place{}, {static_cast<double>(common)});
    ++common;
  }
  st.common = common;
  st.raised = common - first_common;
  for (const auto& c : st.curves) st.repaired += c.repair_rounds > 0 ? 1 : 0;
  return st;
}

Attempt fit_once(const Rows& rows, const FitOptions& o, const Point& bound, int threads) {
  Attempt at;
  const std::size_t M = rows.size();
  auto report = [&](std::string_view stage, std::size_t done, std::size_t total) {
    if (o.progress) o.progress(stage, done, total);
  };
  std::size_t longest = 0;
  for (std::size_t j = 0; j < M; ++j) longest = std::max(longest, rows[j].size());

  // Curve stage on the rows and re-representation on nu (METHOD.md 3-4).
  report("rows", 0, M);
  StageResult rs = run_stage(
      M, [&](std::size_t j) { return rows[j]; }, o.degree_u, o.closed_u, bound, o.search, threads,
      false, longest, o.row_count_hints);
  report("rows", M, M);
  const int nu = rs.common;

  // Transverse stage: column i holds control point i of every row curve (METHOD.md 5).
  std::vector<Point> columns(static_cast<std::size_t>(nu) * M);
  for (std::size_t j = 0; j < M; ++j)
    for (int i = 0; i < nu; ++i)
      columns[static_cast<std::size_t>(i) * M + j] = rs.curves[j].curve.control[i];
  report("columns", 0, static_cast<std::size_t>(nu));
  StageResult cs = run_stage(
      static_cast<std::size_t>(nu),
      [&](std::size_t i) { return std::span<const Point>(columns.data() + i * M, M); }, o.degree_v,
      o.closed_v, bound, o.search, threads, true, M, o.column_count_hints);
  report("columns", static_cast<std::size_t>(nu), static_cast<std::size_t>(nu));
  const int nv = cs.common;

  Surface& s = at.surface;
  s.degree_u = o.degree_u;
  s.degree_v = o.degree_v;
  s.periodic_u = o.closed_u;
  s.periodic_v = o.closed_v;
  s.count_u = nu;
  s.count_v = nv;
  s.control.resize(static_cast<std::size_t>(nu) * nv);
  for (int i = 0; i < nu; ++i)
    for (int l = 0; l < nv; ++l) s.at(i, l) = cs.curves[i].curve.control[l];

  at.v = cs.shared_parameters;
  at.u.resize(rows.total_points());
  for (std::size_t j = 0; j < M; ++j)
    std::copy(rs.curves[j].parameters.begin(), rs.curves[j].parameters.end(),
              at.u.begin() + static_cast<std::ptrdiff_t>(rows.offsets()[j]));

  FitReport& r = at.report;
  r.row_counts = std::move(rs.counts);
  r.column_counts = std::move(cs.counts);
  r.raised_u = rs.raised;
  r.raised_v = cs.raised;
  r.repaired_rows = rs.repaired;
  r.repaired_columns = cs.repaired;
  r.solves = rs.solves + cs.solves;
  return at;
}

}  // namespace

FitResult fit_surface(const Rows& rows, const FitOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  validate(rows, o);
  const int threads = rows.total_points() < 20000 ? 1 : detail::resolve_threads(o.threads);

  // Work on coordinates centred on the bounding box.
  const BoundingBox box = bounding_box(rows);
  const Point centre = 0.5 * (box.min + box.max);
  Rows centred;
  centred.reserve(rows.total_points(), rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (const Point& p : rows[j]) centred.push_point(p - centre);
    centred.end_row();
  }
  const double roundoff = kRoundoffRelative * box.diagonal();

  Attempt at;
  int tightenings = 0;
  DeviationCheck check;
  for (double shrink = 1.0;; shrink *= 0.5) {
    // Stage budget: T/2 with a relative margin so T/2 + T/2 stays <= T after rounding;
    // at T = 0 the round-off allowance.
    Point bound;
    for (int a = 0; a < 3; ++a)
      bound[a] = o.tolerance[a] > 0
                     ? std::max(0.5 * o.tolerance[a] * (1 - 1e-9) * shrink, 0.5 * roundoff)
                     : 0.5 * roundoff;
    at = fit_once(centred, o, bound, threads);
    check = check_deviation(at.surface, centred, at.u, at.v, o.tolerance, roundoff);
    if (check.within || tightenings == 3) break;
    ++tightenings;
  }

  FitResult out;
  out.surface = std::move(at.surface);
  for (Point& p : out.surface.control) p += centre;
  out.u = std::move(at.u);
  out.v = std::move(at.v);
  FitReport& r = out.report;
  r = std::move(at.report);
  r.points = rows.total_points();
  r.rows = rows.size();
  r.tolerance = o.tolerance;
  r.max_deviation = check.max_deviation;
  r.worst_row = check.worst_row;
  r.worst_index = check.worst_index;
  r.worst_deviation = check.worst_deviation;
  r.within_tolerance = check.within;
  r.count_u = out.surface.count_u;
  r.count_v = out.surface.count_v;
  r.degree_u = o.degree_u;
  r.degree_v = o.degree_v;
  r.closed_u = o.closed_u;
  r.closed_v = o.closed_v;
  r.tightenings = tightenings;
  r.roundoff = roundoff;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace sfit
