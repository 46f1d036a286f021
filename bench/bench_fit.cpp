// Speed of the whole fit (fit_surface) by size, search strategy, threads, and incremental
// refit. Run: build/bench/bench_fit (Google Benchmark flags apply), or bench/run.sh.
#include <benchmark/benchmark.h>

#include "sfit/incremental.h"
#include "sfit/io/rows_reader.h"
#include "sfit/surface_fit.h"
#include "synthetic.h"
#include "tensor_lsq.h"

namespace sfit::bench {
namespace {

FitOptions options_for(const Rows& rows, double fraction, int threads = 0) {
  FitOptions o;
  o.tolerance = relative_tolerance(rows, fraction);
  o.threads = threads;
  return o;
}

// Fit time against the number of points (square grids), at 1e-3 of the diagonal.
void BM_FitGrid(benchmark::State& state) {
  const Rows rows = square_grid(state.range(0));
  const FitOptions o = options_for(rows, 1e-3, static_cast<int>(state.range(1)));
  FitResult r;
  for (auto _ : state) r = fit_surface(rows, o);
  state.SetItemsProcessed(state.iterations() * static_cast<long>(rows.total_points()));
  state.counters["nu"] = r.surface.count_u;
  state.counters["nv"] = r.surface.count_v;
  state.counters["held"] = r.report.within_tolerance;
}
BENCHMARK(BM_FitGrid)
    ->ArgsProduct({{100, 1000, 10000, 100000, 1000000}, {1, 2}})
    ->ArgNames({"points", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The same grids with a weight on every point (docs/seams.md): weighted least squares
// factorises every curve afresh (no shared factorisations), the price of weights.
void BM_FitGridWeighted(benchmark::State& state) {
  Rows rows = square_grid(state.range(0));
  std::vector<double> w(rows.total_points());
  for (std::size_t k = 0; k < w.size(); ++k) w[k] = 1 + 0.5 * static_cast<double>(k % 3);
  rows.set_weights(std::move(w));
  const FitOptions o = options_for(rows, 1e-3, 1);
  FitResult r;
  for (auto _ : state) r = fit_surface(rows, o);
  state.SetItemsProcessed(state.iterations() * static_cast<long>(rows.total_points()));
  state.counters["nu"] = r.surface.count_u;
  state.counters["nv"] = r.surface.count_v;
  state.counters["held"] = r.report.within_tolerance;
}
BENCHMARK(BM_FitGridWeighted)
    ->ArgsProduct({{10000, 100000}})
    ->ArgNames({"points"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_FitRagged(benchmark::State& state) {
  const int n = static_cast<int>(std::sqrt(static_cast<double>(state.range(0))));
  const Rows rows = ragged(n, n);
  const FitOptions o = options_for(rows, 1e-3);
  for (auto _ : state) benchmark::DoNotOptimize(fit_surface(rows, o));
  state.SetItemsProcessed(state.iterations() * static_cast<long>(rows.total_points()));
}
// One least-squares solve of the surface search on ragged rows at the chord rule (tensor_lsq.h):
// conjugate gradients with the Kronecker preconditioner (kron_pcg.h) against the sparse
// Cholesky factorisation alone. Args: points, nu = nv, iterative (1) or factorised (0).
void BM_TensorSolveRagged(benchmark::State& state) {
  const int n = static_cast<int>(std::sqrt(static_cast<double>(state.range(0))));
  const Rows rows = ragged(n, n);
  detail::TensorSpec spec;
  spec.rule = Parametrization::kChord;
  spec.iterative = state.range(2) != 0;
  detail::TensorProblem prob(rows, spec);
  const int c = static_cast<int>(state.range(1));
  Surface s;
  prob.solve(c, c, s);  // the moments at nu, cached as in the search
  for (auto _ : state) benchmark::DoNotOptimize(prob.solve(c, c, s));
}
BENCHMARK(BM_TensorSolveRagged)
    ->Args({10000, 20, 1})
    ->Args({10000, 20, 0})
    ->Args({10000, 40, 1})
    ->Args({10000, 40, 0})
    ->Args({100000, 60, 1})
    ->Args({100000, 60, 0})
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_FitRagged)
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The count search (docs/method.md 7.1): the paper's linear search, sfit's default, and the oracle
// (the counts of the final answer given in advance: one solve per curve).
void search_bench(benchmark::State& state, const Rows& rows, Point tol) {
  FitOptions o;
  o.tolerance = tol;
  o.threads = 1;
  const FitResult reference = fit_surface(rows, o);
  const int mode = static_cast<int>(state.range(0));
  o.search = mode == 0   ? CountSearch::kLinear
             : mode == 1 ? CountSearch::kFast
                         : CountSearch::kKnown;
  if (mode == 2) {
    o.row_count_hints = reference.report.row_counts;
    o.column_count_hints = reference.report.column_counts;
  }
  FitResult r;
  for (auto _ : state) r = fit_surface(rows, o);
  state.counters["solves"] = static_cast<double>(r.report.solves);
  state.counters["nu"] = r.surface.count_u;
  state.counters["nv"] = r.surface.count_v;
}

void BM_SearchTable1(benchmark::State& state) {
  static const Rows rows = io::read_rows(SFIT_EXAMPLES_DIR "/table1_synthetic.rows").rows;
  search_bench(state, rows, Point::Constant(1.0));
}
BENCHMARK(BM_SearchTable1)
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("linear0_fast1_oracle2")
    ->Unit(benchmark::kMicrosecond);

void BM_SearchGrid1e5(benchmark::State& state) {
  static const Rows rows = grid(316, 316);
  search_bench(state, rows, relative_tolerance(rows, 1e-3));
}
BENCHMARK(BM_SearchGrid1e5)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("fast1_oracle2")
    ->Unit(benchmark::kMillisecond);

// Interactive use: one point moved in a 300-point set (10 rows of 30), against a full refit.
void BM_IncrementalMove(benchmark::State& state) {
  const Rows rows = grid(10, 30);
  FitOptions o = options_for(rows, 1e-3, 1);
  IncrementalFit inc(rows, o);
  const Point base = rows[5][14];
  int flip = 0;
  for (auto _ : state) {
    flip ^= 1;
    benchmark::DoNotOptimize(inc.move_point(5, 14, base + Point(0, 0, flip ? 0.2 : 0.0)));
  }
  state.counters["rows_refitted"] = static_cast<double>(inc.rows_refitted());
}
BENCHMARK(BM_IncrementalMove)->Unit(benchmark::kMicrosecond);

void BM_FullRefit300(benchmark::State& state) {
  Rows rows = grid(10, 30);
  const FitOptions o = options_for(rows, 1e-3, 1);
  const Point base = rows[5][14];
  int flip = 0;
  for (auto _ : state) {
    flip ^= 1;
    rows.mutable_row(5)[14] = base + Point(0, 0, flip ? 0.2 : 0.0);
    benchmark::DoNotOptimize(fit_surface(rows, o));
  }
}
BENCHMARK(BM_FullRefit300)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sfit::bench

BENCHMARK_MAIN();
