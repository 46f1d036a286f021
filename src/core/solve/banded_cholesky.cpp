// The banded Cholesky factorisation (banded_cholesky.h).
#include "banded_cholesky.h"

#include <algorithm>
#include <cmath>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SFIT_AVX2_CHOLESKY 1
#endif

namespace sfit::detail {

namespace {

double* row_of(double* L, long r, long b) {
  return L + r * (b + 1) - r + b;  // row_of(r)[c] = L(r, c)
}

// L(r, c) from the dot product of rows r and c before c: the root on the diagonal.
bool entry(double* Lr, const double* Lc, long r, long c, double dot, double floor) {
  const double sum = Lr[c] - dot;
  if (c == r) {
    if (!(sum > floor)) return false;
    Lr[c] = std::sqrt(sum);
  } else {
    Lr[c] = sum / Lc[c];
  }
  return true;
}

bool plain(double* L, long N, long b, double floor) {
  for (long r = 0; r < N; ++r) {
    double* Lr = row_of(L, r, b);
    for (long c = std::max(0L, r - b); c <= r; ++c) {
      const double* Lc = row_of(L, c, b);
      // Four partial sums: the dot product vectorises (fixed order: the same bits each run).
      double s4[4] = {0, 0, 0, 0};
      long k = std::max(0L, r - b);
      for (; k + 4 <= c; k += 4)
        for (int e = 0; e < 4; ++e) s4[e] += Lr[k + e] * Lc[k + e];
      for (; k < c; ++k) s4[0] += Lr[k] * Lc[k];
      if (!entry(Lr, Lc, r, c, (s4[0] + s4[1]) + (s4[2] + s4[3]), floor)) return false;
    }
  }
  return true;
}

#ifdef SFIT_AVX2_CHOLESKY

// The dot product's end from the partial sums `acc` at k: blocks of 4 while k + 4 <= end,
// the tail into the first sum (as plain()).
__attribute__((target("avx2"))) double finish(__m256d acc, const double* a, const double* c, long k,
                                              long end) {
  for (; k + 4 <= end; k += 4)
    acc = _mm256_add_pd(acc, _mm256_mul_pd(_mm256_loadu_pd(a + k), _mm256_loadu_pd(c + k)));
  double s[4];
  _mm256_storeu_pd(s, acc);
  for (; k < end; ++k) s[0] += a[k] * c[k];
  return (s[0] + s[1]) + (s[2] + s[3]);
}

// Rows r .. r + R - 1 together: each column c below r is read once for all R rows (each row
// with its own start, so its own partial sums), then the triangle among the R rows.
template <int R>
__attribute__((target("avx2"))) bool rows_at(double* L, long r, long b, double floor) {
  double* Li[R];
  long si[R];
  for (int i = 0; i < R; ++i) {
    Li[i] = row_of(L, r + i, b);
    si[i] = std::max(0L, r + i - b);
  }
  const auto one = [&](int i, long c) __attribute__((target("avx2"))) {
    const double* Lc = row_of(L, c, b);
    return entry(Li[i], Lc, r + i, c, finish(_mm256_setzero_pd(), Li[i], Lc, si[i], c), floor);
  };
  for (long c = si[0]; c < std::min(si[R - 1], r); ++c)  // (columns before the block)
    for (int i = 0; i < R; ++i)
      if (si[i] <= c && !one(i, c)) return false;
  long c = si[R - 1];
  // Two columns c, c + 1 at a time: each row's block read once for both. Column c + 1's dot
  // product runs over the same blocks as column c's here (all before c), and goes on in
  // finish() once L(r + i, c) is known: each partial sum the same products in the same order.
  for (; c + 1 < r; c += 2) {
    const double* Lc = row_of(L, c, b);
    const double* Ld = row_of(L, c + 1, b);
    __m256d acc[R], add[R];
    for (int i = 0; i < R; ++i) acc[i] = add[i] = _mm256_setzero_pd();
    long m = 0;
    for (; si[R - 1] + m + 4 <= c; m += 4)
      for (int i = 0; i < R; ++i) {
        __m256d a = _mm256_loadu_pd(Li[i] + si[i] + m);
        __asm__("" : "+x"(a));  // (kept in a register: the columns' blocks are the operands)
        acc[i] = _mm256_add_pd(acc[i], _mm256_mul_pd(a, _mm256_loadu_pd(Lc + si[i] + m)));
        add[i] = _mm256_add_pd(add[i], _mm256_mul_pd(a, _mm256_loadu_pd(Ld + si[i] + m)));
      }
    for (int i = 0; i < R; ++i) {
      if (!entry(Li[i], Lc, r + i, c, finish(acc[i], Li[i], Lc, si[i] + m, c), floor)) return false;
      if (!entry(Li[i], Ld, r + i, c + 1, finish(add[i], Li[i], Ld, si[i] + m, c + 1), floor))
        return false;
    }
  }
  for (; c < r; ++c) {
    const double* Lc = row_of(L, c, b);
    __m256d acc[R];
    for (int i = 0; i < R; ++i) acc[i] = _mm256_setzero_pd();
    long m = 0;
    for (; si[R - 1] + m + 4 <= c; m += 4)
      for (int i = 0; i < R; ++i)
        acc[i] = _mm256_add_pd(acc[i], _mm256_mul_pd(_mm256_loadu_pd(Li[i] + si[i] + m),
                                                     _mm256_loadu_pd(Lc + si[i] + m)));
    for (int i = 0; i < R; ++i)
      if (!entry(Li[i], Lc, r + i, c, finish(acc[i], Li[i], Lc, si[i] + m, c), floor)) return false;
  }
  for (int j = 0; j < R; ++j)
    for (int i = j; i < R; ++i)
      if (r + j >= si[i] && !one(i, r + j)) return false;  // (within row i's band)
  return true;
}

// banded_substitute() of three right-hand sides, each Point's x, y, z in lanes 0-2 (lane 3
// neither read nor written: masked): per lane the template's operations in its order.
__attribute__((target("avx2"))) void substitute_wide(const double* L, long N, long b,
                                                     Eigen::Vector3d* x) {
  const long w1 = b + 1;
  const __m256i three = _mm256_setr_epi64x(-1, -1, -1, 0);
  auto load = [&](const Eigen::Vector3d& p) __attribute__((target("avx2"))) {
    return _mm256_maskload_pd(p.data(), three);
  };
  for (long r = 0; r < N; ++r) {
    const double* Lr = L + r * w1 - r + b;
    __m256d sum = load(x[r]);
    long k = std::max(0L, r - b);
    for (; k + 2 <= r; k += 2) {  // (two at a time: the same order)
      sum = _mm256_sub_pd(sum, _mm256_mul_pd(_mm256_broadcast_sd(Lr + k), load(x[k])));
      sum = _mm256_sub_pd(sum, _mm256_mul_pd(_mm256_broadcast_sd(Lr + k + 1), load(x[k + 1])));
    }
    if (k < r) sum = _mm256_sub_pd(sum, _mm256_mul_pd(_mm256_broadcast_sd(Lr + k), load(x[k])));
    _mm256_maskstore_pd(x[r].data(), three, _mm256_div_pd(sum, _mm256_broadcast_sd(Lr + r)));
  }
  for (long r = N - 1; r >= 0; --r) {
    const double* Lr = L + r * w1 - r + b;
    const __m256d xr = _mm256_div_pd(load(x[r]), _mm256_broadcast_sd(Lr + r));
    _mm256_maskstore_pd(x[r].data(), three, xr);
    long k = std::max(0L, r - b);
    for (; k + 2 <= r; k += 2) {  // (each x[k] its own update: any grouping, the same bits)
      _mm256_maskstore_pd(
          x[k].data(), three,
          _mm256_sub_pd(load(x[k]), _mm256_mul_pd(_mm256_broadcast_sd(Lr + k), xr)));
      _mm256_maskstore_pd(
          x[k + 1].data(), three,
          _mm256_sub_pd(load(x[k + 1]), _mm256_mul_pd(_mm256_broadcast_sd(Lr + k + 1), xr)));
    }
    if (k < r)
      _mm256_maskstore_pd(
          x[k].data(), three,
          _mm256_sub_pd(load(x[k]), _mm256_mul_pd(_mm256_broadcast_sd(Lr + k), xr)));
  }
}

__attribute__((target("avx2"))) bool wide(double* L, long N, long b, double floor) {
  long r = 0;
  for (; r + 4 <= N; r += 4)
    if (!rows_at<4>(L, r, b, floor)) return false;
  for (; r < N; ++r)
    if (!rows_at<1>(L, r, b, floor)) return false;
  return true;
}

#endif

}  // namespace

bool banded_cholesky(double* L, long N, long b, double floor, bool allow_wide) {
#ifdef SFIT_AVX2_CHOLESKY
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2 && allow_wide) return wide(L, N, b, floor);
#else
  (void)allow_wide;
#endif
  return plain(L, N, b, floor);
}

void banded_substitute(const double* L, long N, long b, Eigen::Vector3d* x, bool allow_wide) {
#ifdef SFIT_AVX2_CHOLESKY
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2 && allow_wide) {
    substitute_wide(L, N, b, x);
    return;
  }
#else
  (void)allow_wide;
#endif
  banded_substitute<Eigen::Vector3d>(L, N, b, x);
}

}  // namespace sfit::detail
