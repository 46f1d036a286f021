// Nearest-neighbour search among 3D points through a uniform bucket grid.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "sfit/rows.h"

namespace sfit::render::detail {

using Cell = Eigen::Array<long, 3, 1>;

/// The nearest of a fixed set of points to a query point (exact, not approximate): buckets of
/// about two points each, searched in growing shells around the query's bucket.
class NearestPoint {
 public:
  explicit NearestPoint(std::vector<Point> samples) : samples_(std::move(samples)) {
    lo_ = hi_ = samples_.front();
    for (const Point& p : samples_) {
      lo_ = lo_.cwiseMin(p);
      hi_ = hi_.cwiseMax(p);
    }
    const Point ext = hi_ - lo_;
    const double big = std::max(ext.maxCoeff(), 1e-300);
    // About two samples a bucket if the samples filled the box's occupied axes.
    int dims = 0;
    double vol = 1;
    for (int a = 0; a < 3; ++a)
      if (ext[a] > 1e-6 * big) {
        ++dims;
        vol *= ext[a];
      }
    cell_ = dims == 0 ? 1.0 : std::pow(vol / (0.5 * samples_.size()), 1.0 / dims);
    cell_ = std::max(cell_, 1e-9 * big);
    for (int a = 0; a < 3; ++a) n_[a] = std::max(1L, static_cast<long>(ext[a] / cell_) + 1);
    for (std::size_t i = 0; i < samples_.size(); ++i)
      buckets_[key(cell_of(samples_[i]))].push_back(i);
  }

  /// Index of the point nearest q (the first of equals). The set must not be empty.
  std::size_t nearest(const Point& q) const { return k_nearest(q, 1).front(); }

  /// Indices of the k points nearest q, nearest first (fewer if the set is smaller).
  std::vector<std::size_t> k_nearest(const Point& q, std::size_t k) const {
    k = std::min(k, samples_.size());
    std::vector<std::pair<double, std::size_t>> best;  // max-heap on distance, at most k
    const Cell c = cell_of(q);
    for (long r = 0;; ++r) {
      // Shell r: cells at Chebyshev distance r from c.
      for (long x = c[0] - r; x <= c[0] + r; ++x)
        for (long y = c[1] - r; y <= c[1] + r; ++y)
          for (long z = c[2] - r; z <= c[2] + r; ++z) {
            if (std::max({std::abs(x - c[0]), std::abs(y - c[1]), std::abs(z - c[2])}) != r)
              continue;
            if (x < 0 || y < 0 || z < 0 || x >= n_[0] || y >= n_[1] || z >= n_[2]) continue;
            const auto it = buckets_.find(key({x, y, z}));
            if (it == buckets_.end()) continue;
            for (std::size_t i : it->second) {
              const double d = (samples_[i] - q).squaredNorm();
              if (best.size() < k) {
                best.emplace_back(d, i);
                std::push_heap(best.begin(), best.end());
              } else if (d < best.front().first) {
                std::pop_heap(best.begin(), best.end());
                best.back() = {d, i};
                std::push_heap(best.begin(), best.end());
              }
            }
          }
      // Unvisited cells are at least r cells from q's (clamped) cell; a q outside the box is
      // farther still (Pythagoras with its projection onto the box).
      const double reach2 = (r * cell_) * (r * cell_) + outside2(q);
      if ((best.size() == k && best.front().first <= reach2) || r > n_.maxCoeff()) break;
    }
    std::sort_heap(best.begin(), best.end());
    std::vector<std::size_t> out;
    for (const auto& b : best) out.push_back(b.second);
    return out;
  }

 private:
  Cell cell_of(const Point& p) const {
    Cell c;
    for (int a = 0; a < 3; ++a)
      c[a] = std::clamp(static_cast<long>(std::floor((p[a] - lo_[a]) / cell_)), 0L, n_[a] - 1);
    return c;
  }
  // Squared distance of q from the grid's box.
  double outside2(const Point& q) const {
    return (q - q.cwiseMax(lo_).cwiseMin(hi_)).squaredNorm();
  }
  long key(const Cell& c) const { return (c[2] * n_[1] + c[1]) * n_[0] + c[0]; }

  std::vector<Point> samples_;
  Point lo_, hi_;
  double cell_ = 1;
  Cell n_;
  std::unordered_map<long, std::vector<std::size_t>> buckets_;
};

}  // namespace sfit::render::detail
