// The two passes over every point that bound the surface search's speed, one core each, in
// points per second: the least-squares pass (TensorProblem's moments at a new nu: every
// point's basis, B^T B and B^T D; about 2 (p+1)^2 + 3 (p+1) multiply-adds per point, bicubic
// 44, plus the basis) and the final check (every point's surface point, (p+1)(q+1) x 3 = 48
// multiply-adds bicubic once the row's iso-curve is made, and its deviation). The limit the
// speed issue states: about 200 multiply-adds per point for one bicubic least-squares pass,
// 30-50 million points per second per core. Run: build/bench/bench_passes.
#include <benchmark/benchmark.h>

#include "deviation.h"
#include "sfit/surface_fit.h"
#include "synthetic.h"
#include "tensor_lsq.h"

namespace sfit::bench {
namespace {

// Arg 0: a grid at the uniform rule (one Gram matrix, the rows' B^T D per point); 1: ragged
// rows at the chord rule (a Gram matrix per row).
Rows rows_for(long kind) {
  return kind == 0 ? square_grid(1000000) : ragged(1000, 1000);
}

void BM_LeastSquaresPass(benchmark::State& state) {
  const Rows rows = rows_for(state.range(0));
  detail::TensorSpec spec;
  spec.rule = state.range(0) == 0 ? Parametrization::kUniform : Parametrization::kChord;
  spec.threads = 1;
  detail::TensorProblem prob(rows, spec);
  int nu = prob.min_u();
  for (auto _ : state) {
    benchmark::DoNotOptimize(prob.u_at(nu).data());  // a new nu: a whole pass
    if (++nu > prob.max_u()) nu = prob.min_u();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(rows.total_points()));
}
BENCHMARK(BM_LeastSquaresPass)->Arg(0)->Arg(1)->ArgNames({"ragged"})->Unit(benchmark::kMillisecond);

void BM_FinalCheck(benchmark::State& state) {
  const Rows rows = rows_for(state.range(0));
  detail::TensorSpec spec;
  spec.rule = state.range(0) == 0 ? Parametrization::kUniform : Parametrization::kChord;
  spec.threads = 1;
  detail::TensorProblem prob(rows, spec);
  Surface s;
  prob.solve(14, 12, s);
  const std::vector<double> u = prob.u_at(14), v = prob.v_at(12);
  for (auto _ : state)
    benchmark::DoNotOptimize(check_deviation(s, rows, u, v, Point::Constant(1e-3), 1e-12, 1));
  state.SetItemsProcessed(state.iterations() * static_cast<long>(rows.total_points()));
}
BENCHMARK(BM_FinalCheck)->Arg(0)->Arg(1)->ArgNames({"ragged"})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sfit::bench

BENCHMARK_MAIN();
