// The banded Cholesky factorisation of the geometric rule's scattered least squares
// (scattered_lsq.h), L L^T in place in a band store. Private.
//
// METHOD   Row by row, each entry a dot product of two rows of L in four partial sums (the
//          entries k - start mod 4 of the row's band, the tail into the first), added as
//          ((s0 + s1) + (s2 + s3)); then divided by the column's pivot, or its root on the
//          diagonal. On x86-64 with AVX2 (checked at run time) four rows at a time, the four
//          partial sums in one 4-wide register: the same operations in the same order (no
//          fused multiply-add), so the same bits as the plain loop, in about half the time
//          (the factorisation was 30-60 % of the worst fits' time, perf).
#pragma once

namespace sfit::detail {

/// Factorises the band store `L` (N rows of b + 1: L(r, c), c <= r, r - c <= b, at
/// L[r (b + 1) + c - r + b]) in place. False at a pivot at or below `floor` (round-off).
/// `wide` false runs the plain loop on every CPU (the tests compare the two paths).
bool banded_cholesky(double* L, long N, long b, double floor, bool wide = true);

}  // namespace sfit::detail
