// The banded Cholesky factorisation of the geometric rule's scattered least squares
// (scattered_lsq.h) and of the row rules' smaller normal equations (normal_equations.h),
// L L^T in place in a band store, with the ordering both use and the substitution. Private.
//
// METHOD   Row by row, each entry a dot product of two rows of L in four partial sums (the
//          entries k - start mod 4 of the row's band, the tail into the first), added as
//          ((s0 + s1) + (s2 + s3)); then divided by the column's pivot, or its root on the
//          diagonal. On x86-64 with AVX2 (checked at run time) four rows at a time, the four
//          partial sums in one 4-wide register: the same operations in the same order (no
//          fused multiply-add), so the same bits as the plain loop, in about half the time
//          (the factorisation was 30-60 % of the worst fits' time, perf); and two columns at
//          a time, each row's block of four read once for both (the second column's dot
//          product goes on once the first's entry is known).
#pragma once

#include <algorithm>

#include <Eigen/Core>

namespace sfit::detail {

/// The ordering of a tensor product's nu x nv unknowns (degrees p, q) whose band is narrower:
/// u-major (i nv + l, band p nv + q) or v-major (l nu + i, band q nu + p); always v-major where
/// u is closed (its wrap then stays within a block: band (q + 1) nu - 1), never where v is
/// closed (band (p + 1) nv - 1). Not for both closed.
struct BandOrder {
  int nu = 0, nv = 0;
  bool v_major = false;
  long b = 0;  ///< the band, at most nu nv - 1
  long at(int i, int l) const {
    return v_major ? static_cast<long>(l) * nu + i : static_cast<long>(i) * nv + l;
  }
};
inline BandOrder band_order(int p, int q, bool closed_u, bool closed_v, int nu, int nv) {
  BandOrder o;
  o.nu = nu;
  o.nv = nv;
  o.v_major =
      closed_u || (!closed_v && static_cast<long>(q) * nu + p < static_cast<long>(p) * nv + q);
  o.b = closed_u   ? static_cast<long>(q + 1) * nu - 1
        : closed_v ? static_cast<long>(p + 1) * nv - 1
                   : (o.v_major ? static_cast<long>(q) * nu + p : static_cast<long>(p) * nv + q);
  o.b = std::min(o.b, static_cast<long>(nu) * nv - 1);
  return o;
}

/// Factorises the band store `L` (N rows of b + 1: L(r, c), c <= r, r - c <= b, at
/// L[r (b + 1) + c - r + b]) in place. False at a pivot at or below `floor` (round-off).
/// `wide` false runs the plain loop on every CPU (the tests compare the two paths).
bool banded_cholesky(double* L, long N, long b, double floor, bool wide = true);

/// Solves L L^T x = y in place (`x` holds y, in the band's order) for a factor of
/// banded_cholesky(); T a scalar or a vector type (one right-hand side per axis).
template <class T>
void banded_substitute(const double* L, long N, long b, T* x) {
  const long w1 = b + 1;
  for (long r = 0; r < N; ++r) {
    const double* Lr = L + r * w1 - r + b;
    T sum = x[r];
    for (long k = std::max(0L, r - b); k < r; ++k) sum -= Lr[k] * x[k];
    x[r] = sum / Lr[r];
  }
  for (long r = N - 1; r >= 0; --r) {
    const double* Lr = L + r * w1 - r + b;
    x[r] /= Lr[r];
    for (long k = std::max(0L, r - b); k < r; ++k) x[k] -= Lr[k] * x[r];
  }
}

/// The same for three right-hand sides (one per axis, the Point type): on x86-64 with AVX2
/// (checked at run time) the three axes in one 4-wide register, the same operations in the
/// same order (no fused multiply-add), so the same bits as the template. `wide` false: the
/// template on every CPU (the tests compare the two).
void banded_substitute(const double* L, long N, long b, Eigen::Vector3d* x, bool wide = true);

}  // namespace sfit::detail
