// The banded Givens least-squares kernel (src/core/solve/banded_lsq.h) against Eigen's SparseQR on
// the same B-spline collocation matrix: the measurement behind keeping our own kernel.
#include <benchmark/benchmark.h>

#include <Eigen/SparseQR>
#include <cmath>
#include <vector>

#include "banded_lsq.h"
#include "basis.h"
#include "parameters.h"

namespace sfit::bench {
namespace {

struct Problem {
  int degree, count, n;
  std::vector<double> basis;
  std::vector<int> first;
  std::vector<Point> data;
};

Problem make(int n, int count, int degree) {
  Problem p{degree, count, n, {}, {}, {}};
  const auto t = paper_parameters(degree, count, false, n);
  p.basis.resize(static_cast<std::size_t>(n) * (degree + 1));
  for (int j = 0; j < n; ++j) {
    p.first.push_back(eval_basis(degree, count, false, t[j],
                                 &p.basis[static_cast<std::size_t>(j) * (degree + 1)]));
    const double s = static_cast<double>(j) / (n - 1);
    p.data.emplace_back(s, std::sin(9 * s), std::cos(5 * s));
  }
  return p;
}

void BM_GivensKernel(benchmark::State& state) {
  const Problem p = make(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), 3);
  std::vector<Point> x;
  for (auto _ : state) {
    detail::BandedLeastSquares lsq(p.count, p.degree + 1, false);
    for (int j = 0; j < p.n; ++j)
      lsq.add(p.first[j], &p.basis[static_cast<std::size_t>(j) * 4], p.data[j]);
    benchmark::DoNotOptimize(lsq.solve(x));
  }
}
BENCHMARK(BM_GivensKernel)
    ->Args({1000, 50})
    ->Args({1000, 200})
    ->Args({10000, 500})
    ->Unit(benchmark::kMicrosecond);

void BM_GivensReplay(benchmark::State& state) {
  // The shared-factorisation path: factor once, replay per right-hand side.
  const Problem p = make(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), 3);
  detail::BandedLeastSquares lsq(p.count, 4, false);
  lsq.record_rotations();
  for (int j = 0; j < p.n; ++j)
    lsq.add(p.first[j], &p.basis[static_cast<std::size_t>(j) * 4], Point::Zero());
  std::vector<Point> x, z;
  for (auto _ : state) benchmark::DoNotOptimize(lsq.replay(p.data.data(), x, z));
}
BENCHMARK(BM_GivensReplay)
    ->Args({1000, 50})
    ->Args({1000, 200})
    ->Args({10000, 500})
    ->Unit(benchmark::kMicrosecond);

void BM_EigenSparseQR(benchmark::State& state) {
  const Problem p = make(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), 3);
  Eigen::MatrixXd B(p.n, 3);
  for (int j = 0; j < p.n; ++j) B.row(j) = p.data[j].transpose();
  for (auto _ : state) {
    std::vector<Eigen::Triplet<double>> trip;
    for (int j = 0; j < p.n; ++j)
      for (int i = 0; i < 4; ++i)
        trip.emplace_back(j, p.first[j] + i, p.basis[static_cast<std::size_t>(j) * 4 + i]);
    Eigen::SparseMatrix<double> A(p.n, p.count);
    A.setFromTriplets(trip.begin(), trip.end());
    A.makeCompressed();
    Eigen::SparseQR<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> qr(A);
    Eigen::MatrixXd X = qr.solve(B);
    benchmark::DoNotOptimize(X.data());
  }
}
BENCHMARK(BM_EigenSparseQR)
    ->Args({1000, 50})
    ->Args({1000, 200})
    ->Args({10000, 500})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sfit::bench

BENCHMARK_MAIN();
