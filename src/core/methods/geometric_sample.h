// The geometric search's sample of large data (docs/method.md 7.9, "Count search, coarse to
// fine"): every step-th point of each row, and its last; and the parameter corrections made
// on the sample carried to every point. Private to the surface search.
#pragma once

#include <cstddef>
#include <vector>

#include "sfit/rows.h"

namespace sfit::detail {

/// Above this many points the pairs are searched on a sample of the rows' points (every
/// step-th of each row, and its last), then verified on all.
inline constexpr std::size_t kSamplePoints = 20000;

/// Rows of the sample, and each sample point's index in the full rows.
struct Sample {
  Rows rows;
  std::vector<std::size_t> index;
};

/// Every step-th point of each row of `rows`, and its last (with its weight where weighted).
Sample take_sample(const Rows& rows, std::size_t step);

/// x at the sample's indices.
template <class T>
std::vector<T> pick(const std::vector<T>& x, const std::vector<std::size_t>& index) {
  std::vector<T> out(index.size());
  for (std::size_t k = 0; k < index.size(); ++k) out[k] = x[index[k]];
  return out;
}

/// The sample's corrections (its fractions fu, fv against fu0, fv0 before them) carried to
/// every point of `rows` (full_u, full_v: the base fractions of every point, corrected in
/// place): linear along each row between the sample points that bracket it; u wrapped where
/// `closed_u`, else clamped to [0, 1], v clamped.
void carry_sample_corrections(const Rows& rows, const std::vector<std::size_t>& index,
                              const std::vector<double>& fu, const std::vector<double>& fv,
                              const std::vector<double>& fu0, const std::vector<double>& fv0,
                              bool closed_u, std::vector<double>& full_u,
                              std::vector<double>& full_v);

}  // namespace sfit::detail
