// The paper's two-stage method (FitMethod::kSfit01, docs/method.md): curve stage on the rows,
// re-representation on a common count, transverse stage on the columns of control points.
// Unchanged in its results by the split into frame and methods (the tests compare bits).
#include <algorithm>
#include <array>
#include <atomic>
#include <functional>
#include <optional>
#include <string>

#include "aligned_fit.h"
#include "basis.h"
#include "deviation.h"
#include "fit_frame.h"
#include "parallel.h"
#include "parameters.h"
#include "rerepresent.h"
#include "sfit/error.h"
#include "sfit/fold_check.h"
#include "surface_fitter.h"

namespace sfit::detail {

namespace {

constexpr std::size_t kBlock = 16;  // curves whose searches chain their starting counts
// [seams] Weights of curve i's points (docs/seams.md); empty function: unweighted.
using WeightsOf = std::function<std::span<const double>(std::size_t)>;

// The minimal fits of curves `todo` (sorted), each starting from its block predecessor's
// count (or from `hints`). Fixed blocks make the result independent of the thread count.
// With `previous` (fits of an earlier pass over the same curves), a curve not in `todo`
// keeps its previous fit unless its predecessor's count changed, in which case it is
// refitted too, exactly as a full pass would. Returns how many curves were fitted.
template <class GetPoints, class GetPositions>
std::size_t fit_curves(std::size_t n_curves, GetPoints&& points_of, GetPositions&& positions_of,
                       const CurveFitOptions& base, const std::vector<int>& hints, int threads,
                       std::vector<CurveFit>& fits, const std::vector<char>* todo,
                       const WeightsOf& weights_of = {}) {
  const bool have_hints = hints.size() == n_curves;
  const std::size_t n_blocks = (n_curves + kBlock - 1) / kBlock;
  fits.resize(n_curves);
  std::vector<std::size_t> fitted(n_blocks, 0);
  // The starting count a fit passes on to the next curve of its block.
  auto passes_on = [&](const CurveFit& f, int previous) {
    return f.curve.degree == base.degree && !f.curve.control.empty() ? f.curve.count() : previous;
  };
  parallel_for(n_blocks, threads, [&](std::size_t b) {
    int previous = 0;      // the hint this pass gives the next curve
    int previous_old = 0;  // the hint the earlier pass gave it
    for (std::size_t i = b * kBlock; i < std::min(n_curves, (b + 1) * kBlock); ++i) {
      const bool must = !todo || (*todo)[i] || (!have_hints && previous != previous_old);
      if (todo) previous_old = passes_on(fits[i], previous_old);
      if (must) {
        CurveFitOptions co = base;
        co.hint = have_hints ? hints[i] : previous;
        co.positions = positions_of(i);
        if (weights_of) co.weights = weights_of(i);  // [seams] weighted least squares
        fits[i] = fit_curve(points_of(i), co);
        ++fitted[b];
      }
      previous = passes_on(fits[i], previous);
    }
  });
  std::size_t n = 0;
  for (std::size_t f : fitted) n += f;
  return n;
}

// The common count is the largest count of any curve, so that one must be the paper's: the
// smallest count that holds (CountSearch::kLinear). The fast search gives a count c that
// holds while c - 1 fails; the smallest count that holds is <= c. Going through the curves
// by decreasing fast count, a curve whose fast count is above the largest linear count found
// so far gets the linear search; the first whose fast count is not stops the pass, since
// neither it nor any after it can raise the maximum. The result: the maximum (and so the
// surface's count) equals the linear search's, at the cost of about one linear search
// (README "Count search"). Bounded: a scan that would cost more point-solves than
// kExactMaximumBudget times the stage's points stops the pass (the fast counts stay), so a
// single row of 10^6 points needing 1000 control points is not searched one count at a time.
template <class GetPoints, class GetPositions>
void exact_maximum(std::vector<CurveFit>& fits, GetPoints&& points_of, GetPositions&& positions_of,
                   const CurveFitOptions& base, int threads, const WeightsOf& weights_of = {}) {
  if (base.search != CountSearch::kFast) return;
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < fits.size(); ++i)
    if (fits[i].curve.degree == base.degree) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return fits[a].curve.count() > fits[b].curve.count();
  });
  int largest = 0;
  CurveFitOptions linear = base;
  linear.search = CountSearch::kLinear;
  constexpr double kExactMaximumBudget = 32;
  double budget = 0;
  for (std::size_t i = 0; i < fits.size(); ++i)
    budget += kExactMaximumBudget * static_cast<double>(points_of(i).size());
  auto cost_of = [&](std::size_t i) {
    return static_cast<double>(fits[i].curve.count() - base.degree) *
           static_cast<double>(points_of(i).size());
  };
  // The pass is sequential (each linear count can end it), so the next `threads` curves it
  // would visit if none ended it are searched at once, and their results are then taken in
  // order under the same rule; a search the rule does not reach is dropped. Same result as
  // one curve at a time, for any thread count.
  const std::size_t batch = static_cast<std::size_t>(std::max(1, threads));
  std::vector<std::size_t> next;
  std::vector<CurveFit> linear_fits;
  for (std::size_t k = 0; k < order.size();) {
    next.clear();
    double left = budget;
    for (std::size_t m = k; m < order.size() && next.size() < batch; ++m) {
      const std::size_t i = order[m];
      if (fits[i].curve.count() <= largest || cost_of(i) > left) break;
      left -= cost_of(i);
      next.push_back(i);
    }
    if (next.empty()) return;
    linear_fits.assign(next.size(), CurveFit{});
    parallel_for(next.size(), threads, [&](std::size_t c) {
      CurveFitOptions o = linear;
      o.positions = positions_of(next[c]);
      if (weights_of) o.weights = weights_of(next[c]);
      linear_fits[c] = fit_curve(points_of(next[c]), o);
    });
    for (std::size_t c = 0; c < next.size(); ++c) {
      const std::size_t i = next[c];
      if (fits[i].curve.count() <= largest || cost_of(i) > budget) return;
      budget -= cost_of(i);
      linear_fits[c].solves += fits[i].solves;
      fits[i] = std::move(linear_fits[c]);
      largest = std::max(largest, fits[i].curve.count());
    }
    k += next.size();
  }
}

// One curve on `count` control points. At the paper's parameters: rerepresent() (docs/method.md
// 4). At positions (docs/method.md 7.4), where the curve has at least `count` points: the least
// squares fit of its points with `count` control points at the same positions, if it holds.
// Every curve's coefficients are then one linear map of its points, so curves whose points
// vary smoothly from one to the next have control points that do too, and the transverse
// stage needs few; the minimal counts differing from curve to curve would otherwise leave
// each curve's own approximation error in its control points. Where the refit does not hold
// (the count's fit is not always within the bound when a smaller one is), rerepresent().
Rerepresentation represent_one(const CurveFit& fit, std::span<const Point> points,
                               std::span<const double> positions, int degree, int count,
                               bool periodic, const Point& bound, std::span<const double> target,
                               bool weighted = false, Resampling resampling = Resampling::kPaper) {
  // A weighted curve keeps its own fit's shape: re-represented, not refitted unweighted.
  if (!weighted && fit.scaled && !positions.empty() && fit.curve.degree == degree &&
      points.size() >= static_cast<std::size_t>(count) && fit.curve.count() != count) {
    CurveFit refit;
    try {
      refit = fit_curve_with_count(points, degree, periodic, count, positions);
    } catch (const Error&) {  // singular at these positions
      refit.curve.control.clear();
    }
    if (!refit.curve.control.empty() && (refit.max_deviation.array() <= bound.array()).all() &&
        (target.empty() || std::equal(target.begin(), target.end(), refit.parameters.begin(),
                                      refit.parameters.end()))) {
      Rerepresentation r;
      r.curve = std::move(refit.curve);
      r.parameters = std::move(refit.parameters);
      r.max_deviation = refit.max_deviation;
      r.holds = true;
      return r;
    }
  }
  return rerepresent(fit, points, degree, count, periodic, bound, target, resampling);
}

// Re-represents every curve on one common count, starting at max(degree + 1, counts) and
// raising it until every curve holds (the guarantee's first half). `reuse` (optional) holds
// earlier re-representations valid at `reuse_count` for curves not marked in `dirty`.
struct Represented {
  std::vector<Rerepresentation> curves;
  int first_common = 0, common = 0;
  int repaired = 0;
  std::vector<double> shared_parameters;
};

template <class GetPoints, class GetPositions>
Represented represent(std::size_t n_curves, GetPoints&& points_of, GetPositions&& positions_of,
                      const std::vector<CurveFit>& fits, int degree, bool periodic,
                      const Point& bound, int threads, bool shared_params, std::size_t max_points,
                      std::span<const double> shared_positions,
                      std::vector<Rerepresentation>* reuse, int reuse_count,
                      const std::vector<char>* dirty, bool weighted = false,
                      Resampling resampling = Resampling::kPaper) {
  Represented st;
  int common = degree + 1;
  for (const auto& f : fits) common = std::max(common, f.curve.count());
  st.first_common = common;
  // At positions a count above the curves' points is not worth trying: the paper's rule,
  // which fit() falls back to, does better there.
  const bool at_positions = n_curves > 0 && !positions_of(0).empty();
  const int cap =
      static_cast<int>(std::max<std::size_t>(max_points, common)) + (at_positions ? 0 : degree + 8);
  st.curves.resize(n_curves);
  while (true) {
    if (shared_params)
      st.shared_parameters =
          shared_positions.empty()
              ? paper_parameters(degree, common, periodic, static_cast<int>(max_points))
              : scaled_parameters(degree, common, periodic, shared_positions);
    // Stop the pass at the first curve that fails: the count is raised whatever the others
    // do, so the outcome (the first count at which every curve holds) is the same.
    std::atomic<bool> failed{false};
    parallel_for(n_curves, threads, [&](std::size_t i) {
      if (failed.load(std::memory_order_relaxed)) return;
      if (reuse && common == reuse_count && !(*dirty)[i]) {
        st.curves[i] = std::move((*reuse)[i]);
      } else {
        st.curves[i] =
            represent_one(fits[i], points_of(i), positions_of(i), degree, common, periodic, bound,
                          shared_params ? std::span<const double>(st.shared_parameters)
                                        : std::span<const double>(),
                          weighted, resampling);
      }
      if (!st.curves[i].holds) failed.store(true, std::memory_order_relaxed);
    });
    if (!failed.load()) break;
    if (reuse && common == reuse_count) reuse = nullptr;  // moved from: compute afresh
    if (common >= cap)
      throw Error(ErrorCode::kToleranceNotMet,
                  "re-representation cannot hold the tolerance even with " +
                      std::to_string(common) + " control points",
                  Place{}, {static_cast<double>(common)});
    ++common;
  }
  st.common = common;
  for (const auto& c : st.curves) st.repaired += c.repair_rounds > 0 ? 1 : 0;
  return st;
}

// [seams] The weights of the columns' points (control point i of row j at [i * M + j]): the
// mean weight of row j's points that control point i influences, each counted by its basis
// value at the point's parameter; the row's mean weight where it influences none. Empty for
// unweighted rows.
std::vector<double> control_weights(const Rows& rows, const std::vector<Rerepresentation>& curves,
                                    int nu, int threads) {
  if (!rows.weighted()) return {};
  const std::size_t M = rows.size();
  std::vector<double> w(static_cast<std::size_t>(nu) * M, 1.0);
  parallel_for(M, threads, [&](std::size_t j) {
    const auto pw = rows.row_weights(j);
    const Curve& c = curves[j].curve;
    std::vector<double> sum(static_cast<std::size_t>(nu), 0.0), mass(sum);
    double mean = 0;
    std::array<double, kMaxDegree + 1> b;
    for (std::size_t k = 0; k < pw.size(); ++k) {
      mean += pw[k] / static_cast<double>(pw.size());
      if (c.degree == 0) continue;
      const int f = eval_basis(c.degree, nu, c.periodic, curves[j].parameters[k], b.data());
      for (int a = 0; a <= c.degree; ++a) {
        const int i = wrap_index(f + a, nu);
        sum[i] += b[a] * pw[k];
        mass[i] += b[a];
      }
    }
    for (int i = 0; i < nu; ++i)
      w[static_cast<std::size_t>(i) * M + j] = mass[i] > 0 ? sum[i] / mass[i] : mean;
  });
  return w;
}

template <class GetPoints>
std::vector<double> averaged_positions(std::size_t n_curves, GetPoints&& points_of,
                                       Parametrization rule, bool periodic) {
  std::vector<double> sum;
  std::size_t used = 0;
  for (std::size_t i = 0; i < n_curves; ++i) {
    const auto pts = points_of(i);
    if (sum.empty()) sum.assign(pts.size(), 0.0);
    bool coincide = true;
    for (const Point& p : pts) coincide = coincide && p == pts[0];
    if (coincide) continue;
    const auto f = normalized_positions(pts, rule, periodic);
    for (std::size_t j = 0; j < f.size(); ++j) sum[j] += f[j];
    ++used;
  }
  if (used == 0) return normalized_positions(points_of(0), Parametrization::kUniform, periodic);
  for (double& f : sum) f /= static_cast<double>(used);
  if (!periodic) sum.back() = 1.0;
  sum.front() = 0.0;
  return sum;
}

}  // namespace

struct SurfaceFitter::Attempt {
  Surface surface;  // centred coordinates
  std::vector<double> u, v;
  FitReport report;
};

void SurfaceFitter::centre(const Rows& rows) {
  threads_ = threads_for(rows, o_.threads);
  box_ = box_of(rows, threads_);
  centre_ = 0.5 * (box_.min + box_.max);
  copy_centred(rows);
  roundoff_ = kRoundoffRelative * box_.diagonal();
}

void SurfaceFitter::copy_centred(const Rows& rows) {
  centred_ = rows;
  parallel_for(rows.size(), threads_, [&](std::size_t j) {
    for (Point& p : centred_.mutable_row(j)) p -= centre_;
  });
}

SurfaceFitter::Attempt SurfaceFitter::fit_once(const Point& bound,
                                               const std::vector<char>* changed) {
  Attempt at;
  const Rows& rows = centred_;
  const std::size_t M = rows.size();
  auto report = [&](std::string_view stage, std::size_t done, std::size_t total) {
    if (o_.progress) o_.progress(stage, done, total);
  };
  std::size_t longest = 0;
  for (std::size_t j = 0; j < M; ++j) longest = std::max(longest, rows[j].size());
  auto row_points = [&](std::size_t j) { return rows[j]; };

  // Positions of the points along their rows (none for the paper's rule): docs/method.md 7.4.
  const bool geometric = rule_ != Parametrization::kPaper;
  // [seams hook] Fractional seams (RowSeam::offset): positions measured from each row's seam
  // (the paper's rule then uses uniform positions, its own to rounding).
  const bool seam_positions = !row_seam_offsets_.empty();
  const bool row_geometric = geometric || seam_positions;
  std::vector<double> row_positions;
  if (row_geometric) {
    row_positions.resize(rows.total_points());
    parallel_for(M, threads_, [&](std::size_t j) {
      auto f =
          normalized_positions(rows[j], geometric ? rule_ : Parametrization::kUniform, o_.closed_u);
      if (seam_positions) shift_positions(f, row_seam_offsets_[j]);
      std::copy(f.begin(), f.end(),
                row_positions.begin() + static_cast<std::ptrdiff_t>(rows.offsets()[j]));
    });
  }
  auto row_positions_of = [&](std::size_t j) {
    if (!row_geometric) return std::span<const double>();
    return std::span<const double>(row_positions.data() + rows.offsets()[j], rows[j].size());
  };

  // Curve stage on the rows (docs/method.md 3): all rows, or the changed ones and their chains.
  report("rows", 0, M);
  CurveFitOptions row_options{o_.degree_u, o_.closed_u, bound, o_.search};
  // Uniform positions depend on the row's length only, so rows of one length share them.
  row_options.shared_positions = rule_ == Parametrization::kUniform;
  std::vector<CurveFit> fits;
  if (changed) fits = row_fits_;
  // [seams hook] Weighted rows: weighted least squares in the curve stage.
  const WeightsOf row_weights_of =
      rows.weighted() ? WeightsOf([&](std::size_t j) { return rows.row_weights(j); }) : WeightsOf();
  rows_refitted_ = fit_curves(M, row_points, row_positions_of, row_options, o_.row_count_hints,
                              threads_, fits, changed, row_weights_of);
  // `fast_fits` (the searches' own results) are what an update chains its hints from.
  std::vector<CurveFit> fast_fits = fits;
  exact_maximum(fits, row_points, row_positions_of, row_options, threads_, row_weights_of);
  // Rows whose fit changed need a new re-representation.
  std::vector<char> dirty(M, 1);
  if (changed)
    for (std::size_t j = 0; j < M; ++j)
      dirty[j] = (*changed)[j] || fits[j].curve.control != row_final_fits_[j].curve.control;
  report("rows", M, M);

  // Re-representation on the common count nu (docs/method.md 4).
  Represented rs =
      represent(M, row_points, row_positions_of, fits, o_.degree_u, o_.closed_u, bound, threads_,
                false, longest, {}, changed ? &row_curves_ : nullptr, row_common_,
                changed ? &dirty : nullptr, rows.weighted(), o_.rerepresentation);
  const int nu = rs.common;

  // Transverse stage: column i holds control point i of every row curve (docs/method.md 5).
  std::vector<Point> columns(static_cast<std::size_t>(nu) * M);
  for (std::size_t j = 0; j < M; ++j)
    for (int i = 0; i < nu; ++i)
      columns[static_cast<std::size_t>(i) * M + j] = rs.curves[j].curve.control[i];
  auto column_points = [&](std::size_t i) {
    return std::span<const Point>(columns.data() + i * M, M);
  };
  // One position per row, shared by every column (the guarantee needs one v per row).
  // [seams hook] The fold guard may set its own rule across the rows (across_).
  const Parametrization across = across_.value_or(rule_);
  const std::vector<double> column_positions =
      across != Parametrization::kPaper
          ? averaged_positions(static_cast<std::size_t>(nu), column_points, across, o_.closed_v)
          : std::vector<double>();
  auto column_positions_of = [&](std::size_t) { return std::span<const double>(column_positions); };
  // [seams hook] Weights across (docs/seams.md): control point i of row j weighs the mean
  // weight of the row's points it influences, each counted by its basis value there.
  const std::vector<double> column_weights = control_weights(rows, rs.curves, nu, threads_);
  const WeightsOf column_weights_of =
      column_weights.empty() ? WeightsOf() : WeightsOf([&](std::size_t i) {
        return std::span<const double>(column_weights.data() + i * M, M);
      });
  report("columns", 0, static_cast<std::size_t>(nu));
  CurveFitOptions column_options{o_.degree_v, o_.closed_v, bound, o_.search};
  column_options.shared_positions = true;
  std::vector<CurveFit> column_fits;
  fit_curves(static_cast<std::size_t>(nu), column_points, column_positions_of, column_options,
             o_.column_count_hints, threads_, column_fits, nullptr, column_weights_of);
  exact_maximum(column_fits, column_points, column_positions_of, column_options, threads_,
                column_weights_of);
  Represented cs = represent(static_cast<std::size_t>(nu), column_points, column_positions_of,
                             column_fits, o_.degree_v, o_.closed_v, bound, threads_, true, M,
                             column_positions, nullptr, 0, nullptr, rows.weighted());
  report("columns", static_cast<std::size_t>(nu), static_cast<std::size_t>(nu));
  const int nv = cs.common;

  Surface& s = at.surface;
  s.degree_u = o_.degree_u;
  s.degree_v = o_.degree_v;
  s.periodic_u = o_.closed_u;
  s.periodic_v = o_.closed_v;
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
  r.row_counts.resize(M);
  r.solves = 0;
  for (std::size_t j = 0; j < M; ++j) {
    r.row_counts[j] = fits[j].curve.count();
    r.solves += fits[j].solves;
  }
  r.column_counts.resize(static_cast<std::size_t>(nu));
  for (int i = 0; i < nu; ++i) {
    r.column_counts[i] = column_fits[i].curve.count();
    r.solves += column_fits[i].solves;
  }
  r.raised_u = rs.common - rs.first_common;
  r.raised_v = cs.common - cs.first_common;
  r.repaired_rows = rs.repaired;
  r.repaired_columns = cs.repaired;

  // Keep the row stage for update(): fits, and re-representations at nu.
  row_fits_ = std::move(fast_fits);
  row_final_fits_ = std::move(fits);
  row_curves_ = rs.curves;
  row_common_ = nu;
  return at;
}

FitResult SurfaceFitter::finish(Attempt& at, int tightenings, const DeviationCheck& check,
                                double seconds_start) const {
  FitResult out;
  out.surface = std::move(at.surface);
  for (Point& p : out.surface.control) p += centre_;
  out.u = std::move(at.u);
  out.v = std::move(at.v);
  FitReport& r = out.report;
  r = std::move(at.report);
  r.points = centred_.total_points();
  r.rows = centred_.size();
  r.tolerance = o_.tolerance;
  r.max_deviation = check.max_deviation;
  r.worst_row = check.worst_row;
  r.worst_index = check.worst_index;
  r.worst_deviation = check.worst_deviation;
  r.within_tolerance = check.within;
  r.count_u = out.surface.count_u;
  r.count_v = out.surface.count_v;
  r.degree_u = o_.degree_u;
  r.degree_v = o_.degree_v;
  r.closed_u = o_.closed_u;
  r.closed_v = o_.closed_v;
  r.parametrization = rule_;
  r.parametrization_across = across_.value_or(rule_);
  r.tightenings = tightenings;
  r.roundoff = roundoff_;
  {  // [seams hook] Shape measures (fold_check.h) on the centred surface and rows.
    const BoundingBox box{box_.min - centre_, box_.max - centre_};
    Surface centred = out.surface;
    for (Point& p : centred.control) p -= centre_;
    const ShapeMeasures m = measure_shape(centred, centred_, out.u, out.v, box, o_.closed_u);
    r.fold = m.fold;
    r.box_excursion = m.box_excursion;
    r.row_gap = m.row_gap;
  }
  r.seconds = now() - seconds_start;
  return out;
}

namespace {
long size_of(const FitResult& f) {
  return static_cast<long>(f.surface.count_u) * f.surface.count_v;
}
}  // namespace

FitResult SurfaceFitter::fit(const Rows& rows) {
  // [seams hook] Seam alignment and orientation (seam_alignment.h, docs/seams.md), for every
  // method: the fit runs on the re-ordered rows; u, the worst point and the report refer to
  // the original points. update() refits in full after an aligned fit (valid_ cleared).
  if (o_.seam != SeamMode::kKeep || o_.orient != OrientMode::kKeep) {
    const RowAlignment a = alignment_for(rows, o_);
    if (!a.identity()) {
      validate(rows, o_);  // errors name the original rows and points
      row_seam_offsets_ = seam_offsets(a, o_.closed_u);
      FitResult r = fit_given(apply_alignment(rows, a));
      row_seam_offsets_.clear();
      restore_original_order(r, rows, a);
      valid_ = false;
      return r;
    }
  }
  return fit_given(rows);
}

FitResult SurfaceFitter::fit_given(const Rows& rows) {
  if (o_.method == FitMethod::kSurface) {
    // The surface search has no per-row state to reuse: update() refits in full.
    valid_ = false;
    rows_refitted_ = rows.size();
    FitOptions o = o_;  // the rows are aligned already (fit())
    o.seam = SeamMode::kKeep;
    o.orient = OrientMode::kKeep;
    return fit_surface_search(rows, o, row_seam_offsets_);
  }
  if (o_.parametrization != Parametrization::kFewest) return fit_rule(rows, o_.parametrization);
  // Every rule in turn; the surface with the fewest control points wins (the first rule on a
  // tie, the paper's first). update() then refits in full (valid_ is cleared), which is what
  // this does.
  const double t0 = now();
  std::optional<FitResult> best;
  for (Parametrization rule : {Parametrization::kPaper, Parametrization::kUniform,
                               Parametrization::kChord, Parametrization::kCentripetal}) {
    FitResult r = fit_rule(rows, rule);
    const auto size = [](const FitResult& f) {
      return static_cast<long>(f.surface.count_u) * f.surface.count_v;
    };
    // [seams] Within tolerance first, then fold-free, then the fewest control points.
    const auto rank = [&](const FitResult& f) {
      return 2 * !f.report.within_tolerance + (o_.fold_guard && folds(f));
    };
    if (!best || rank(r) < rank(*best) || (rank(r) == rank(*best) && size(r) < size(*best)))
      best = std::move(r);
  }
  valid_ = false;
  best->report.seconds = now() - t0;
  return std::move(*best);
}

FitResult SurfaceFitter::fit_rule(const Rows& rows, Parametrization requested) {
  // [seams hook] The fold guard (fold_check.h, docs/seams.md): a surface that doubles back on
  // itself between rows is refitted with chord-length, then centripetal, positions across the
  // rows (uneven row spacing at the paper's even v is what folds it); the fold-free one with
  // the fewest control points wins. Where none is fold-free, the least folded stays and its
  // report.fold says by how much (the CLI warns).
  const double t0 = now();
  FitResult r = fit_rule_unguarded(rows, requested);
  if (!o_.fold_guard || !folds(r)) return r;
  const Parametrization used = rule_;
  std::optional<FitResult> best;
  for (Parametrization across : {Parametrization::kChord, Parametrization::kCentripetal}) {
    across_ = across;
    try {
      FitResult c = fit_rule_unguarded(rows, requested);
      if (c.report.within_tolerance && !folds(c) && stays_near_the_data(c.surface, box_) &&
          (!best || size_of(c) < size_of(*best)))
        best = std::move(c);
    } catch (const Error& e) {
      if (e.code() != ErrorCode::kToleranceNotMet) throw;
    }
  }
  across_.reset();
  valid_ = false;  // update() refits in full
  if (!best) {
    rule_ = used;
    r.report.seconds = now() - t0;
    return r;
  }
  rule_ = best->report.parametrization;
  best->report.seconds = now() - t0;
  return std::move(*best);
}

bool SurfaceFitter::folds(const FitResult& r) const {
  return r.report.fold > kFoldRelative * box_.diagonal();
}

FitResult SurfaceFitter::fit_rule_unguarded(const Rows& rows, Parametrization requested) {
  rule_ = requested;
  if (rule_ == Parametrization::kPaper) return fit_with_rule(rows);
  // The geometric rules (docs/method.md 7.4) hold the tolerance on their own where they can; where
  // they cannot (a re-representation or the final check fails: positions whose systems are
  // singular near interpolation, rows whose parameters disagree), or where the surface swings
  // away between the points it holds (the frame's guards, failed_guard()), the paper's rule, which
  // always can, fits instead; the report names the rule used. report.seconds covers all of it: the
  // check below, and a failed attempt before a fallback.
  const double t0 = now();
  try {
    FitResult r = fit_with_rule(rows);
    if (r.report.within_tolerance && !failed_guard(r.surface, box_) &&
        !(o_.fold_guard && folds(r))) {
      r.report.seconds = now() - t0;
      return r;
    }
  } catch (const Error& e) {
    if (e.code() != ErrorCode::kToleranceNotMet) throw;
  }
  rule_ = Parametrization::kPaper;
  FitResult r = fit_with_rule(rows);
  r.report.seconds = now() - t0;
  return r;
}

FitResult SurfaceFitter::fit_with_rule(const Rows& rows) {
  const double t0 = now();
  validate(rows, o_);
  centre(rows);
  Attempt at;
  int tightenings = 0;
  DeviationCheck check;
  valid_ = false;
  for (double shrink = 1.0;; shrink *= 0.5) {
    // Stage budget: T/2 with a relative margin so T/2 + T/2 stays <= T after rounding;
    // at T = 0 the round-off allowance.
    Point bound;
    for (int a = 0; a < 3; ++a)
      bound[a] = o_.tolerance[a] > 0
                     ? std::max(0.5 * o_.tolerance[a] * (1 - 1e-9) * shrink, 0.5 * roundoff_)
                     : 0.5 * roundoff_;
    at = fit_once(bound, nullptr);
    if (tightenings == 0) {
      bound_ = bound;
      valid_ = true;
    } else {
      valid_ = false;  // the kept state is not the first attempt's
    }
    check = check_deviation(at.surface, centred_, at.u, at.v, o_.tolerance, roundoff_, threads_);
    if (check.within || tightenings == 3) break;
    ++tightenings;
  }
  return finish(at, tightenings, check, t0);
}

FitResult SurfaceFitter::update(const Rows& rows, const std::vector<std::size_t>& changed) {
  const double t0 = now();
  validate(rows, o_);
  const int threads = threads_for(rows, o_.threads);
  const BoundingBox box = box_of(rows, threads);
  if (!valid_ || rows.size() != centred_.size() || box.min != box_.min || box.max != box_.max ||
      rule_ != o_.parametrization)  // (never equal for kFewest: full refits)
    return fit(rows);
  // [seams hook] Rows that need re-ordering: a full fit (fit() aligns them).
  if (!alignment_for(rows, o_).identity()) return fit(rows);
  // Same box, so the same centre, round-off allowance and budget: refresh the edited rows.
  std::vector<char> mark(rows.size(), 0);
  for (std::size_t j : changed) mark.at(j) = 1;
  valid_ = false;  // until the update completes
  threads_ = threads;
  copy_centred(rows);
  Attempt at;
  try {
    at = fit_once(bound_, &mark);
  } catch (const Error& e) {
    if (e.code() != ErrorCode::kToleranceNotMet) throw;
    return fit(rows);  // fit() would have met the same failure first: do exactly what it does
  }
  const DeviationCheck check =
      check_deviation(at.surface, centred_, at.u, at.v, o_.tolerance, roundoff_, threads_);
  if (!check.within) return fit(rows);  // fit() would tighten: do exactly that
  FitResult out = finish(at, 0, check, t0);
  if (rule_ != Parametrization::kPaper && failed_guard(out.surface, box_))
    return fit(rows);  // fit() falls back to the paper's rule: do exactly that
  if (o_.fold_guard && folds(out)) return fit(rows);  // [seams hook] fit() guards the fold
  valid_ = true;
  return out;
}

}  // namespace sfit::detail
