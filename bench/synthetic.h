// Deterministic synthetic data for the benchmarks: smooth terrain-like grids and ragged
// section sets of any size.
#pragma once

#include <cmath>
#include <cstdint>

#include "sfit/rows.h"

namespace sfit::bench {

/// A smooth surface over [0, 100]^2 with features at several scales.
inline Point terrain(double s, double t) {
  return Point(
      100 * s, 100 * t,
      10 * std::sin(3 * s) * std::cos(2 * t) + 5 * s * t * t + 0.5 * std::sin(17 * s + 11 * t));
}

/// M rows of N points each on terrain().
inline Rows grid(int M, int N) {
  Rows rows;
  rows.reserve(static_cast<std::size_t>(M) * N, M);
  for (int j = 0; j < M; ++j) {
    for (int k = 0; k < N; ++k)
      rows.push_point(terrain(static_cast<double>(k) / (N - 1), static_cast<double>(j) / (M - 1)));
    rows.end_row();
  }
  return rows;
}

/// M rows of ragged lengths around N (from 0.6 N to 1.4 N), on terrain().
inline Rows ragged(int M, int N) {
  Rows rows;
  std::uint32_t state = 12345;
  for (int j = 0; j < M; ++j) {
    state = state * 1664525u + 1013904223u;
    const int n = std::max(4, static_cast<int>(N * (0.6 + 0.8 * (state >> 8) / double(1 << 24))));
    for (int k = 0; k < n; ++k)
      rows.push_point(terrain(static_cast<double>(k) / (n - 1), static_cast<double>(j) / (M - 1)));
    rows.end_row();
  }
  return rows;
}

/// The grid closest to `points` points with M = N.
inline Rows square_grid(long points) {
  const int n = std::max(4, static_cast<int>(std::lround(std::sqrt(static_cast<double>(points)))));
  return grid(n, n);
}

}  // namespace sfit::bench
