// The transverse stage (transverse_stage.h, docs/method.md 5).
#include "transverse_stage.h"

#include <array>

#include "basis.h"
#include "parallel.h"
#include "sfit/parametrization.h"

namespace sfit::detail {

namespace {

// The weights of the columns' points (control point i of row j at [i * M + j]): the
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

// Positions across the rows for the geometric rules (docs/method.md 7.4): each column's
// normalized_positions(), averaged over the columns whose points do not all coincide (Piegl
// and Tiller, The NURBS Book 9.2.5); uniform where every column's points coincide.
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

Columns fit_columns(const Rows& rows, const std::vector<Rerepresentation>& row_curves, int nu,
                    Parametrization across, const FitOptions& o, const Point& bound, int threads,
                    std::vector<Rerepresentation>* release) {
  const std::size_t M = rows.size();
  auto report = [&](std::string_view stage, std::size_t done, std::size_t total) {
    if (done == 0) {
      progress_phase(stage, total);
    } else {
      progress_advance(done);
    }
  };
  // Column i holds control point i of every row curve.
  std::vector<Point> columns(static_cast<std::size_t>(nu) * M);
  for (std::size_t j = 0; j < M; ++j)
    for (int i = 0; i < nu; ++i)
      columns[static_cast<std::size_t>(i) * M + j] = row_curves[j].curve.control[i];
  auto column_points = [&](std::size_t i) {
    return std::span<const Point>(columns.data() + i * M, M);
  };
  // One position per row, shared by every column (the guarantee needs one v per row).
  const std::vector<double> column_positions =
      across != Parametrization::kPaper
          ? averaged_positions(static_cast<std::size_t>(nu), column_points, across, o.closed_v)
          : std::vector<double>();
  auto column_positions_of = [&](std::size_t) { return std::span<const double>(column_positions); };
  // Weights across (docs/seams.md): control point i of row j weighs the mean
  // weight of the row's points it influences, each counted by its basis value there.
  const std::vector<double> column_weights = control_weights(rows, row_curves, nu, threads);
  if (release)
    for (Rerepresentation& c : *release) std::vector<Point>().swap(c.curve.control);
  const WeightsOf column_weights_of =
      column_weights.empty() ? WeightsOf() : WeightsOf([&](std::size_t i) {
        return std::span<const double>(column_weights.data() + i * M, M);
      });
  report("columns", 0, static_cast<std::size_t>(nu));
  CurveFitOptions column_options{o.degree_v, o.closed_v, bound, o.search};
  column_options.shared_positions = true;
  Columns out;
  fit_curves(static_cast<std::size_t>(nu), column_points, column_positions_of, column_options,
             o.column_count_hints, threads, out.fits, nullptr, column_weights_of);
  exact_maximum(out.fits, column_points, column_positions_of, column_options, threads,
                column_weights_of);
  out.represented = represent(static_cast<std::size_t>(nu), column_points, column_positions_of,
                              out.fits, o.degree_v, o.closed_v, bound, threads, true, M,
                              column_positions, nullptr, 0, nullptr, rows.weighted());
  report("columns", static_cast<std::size_t>(nu), static_cast<std::size_t>(nu));
  return out;
}

}  // namespace sfit::detail
