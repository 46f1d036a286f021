// Points and the ragged container of rows (docs/method.md section 1).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

namespace sfit {

/// A point or a per-axis quantity (x, y, z).
using Point = Eigen::Vector3d;

/// M rows of 3D points, row j holding N_j >= 1 points; rows may differ in length.
/// Stored contiguously (one array of points plus row offsets), so 10^7 points cost
/// 24 bytes each and nothing per row beyond one offset. u runs along a row, v across rows.
class Rows {
 public:
  Rows() { offsets_.push_back(0); }

  /// Appends a row (a copy of `points`).
  void add_row(std::span<const Point> points) {
    points_.insert(points_.end(), points.begin(), points.end());
    offsets_.push_back(points_.size());
  }
  /// Appends one point to the row being built; close it with end_row().
  void push_point(const Point& p) { points_.push_back(p); }
  /// Closes the row being built (the points pushed since the last end_row()).
  void end_row() { offsets_.push_back(points_.size()); }
  /// Number of points pushed since the last end_row().
  std::size_t open_row_size() const { return points_.size() - offsets_.back(); }

  /// Number of rows M.
  std::size_t size() const { return offsets_.size() - 1; }
  bool empty() const { return size() == 0; }
  /// Row j as a span of points.
  std::span<const Point> operator[](std::size_t j) const {
    return {points_.data() + offsets_[j], offsets_[j + 1] - offsets_[j]};
  }
  std::span<Point> mutable_row(std::size_t j) {
    return {points_.data() + offsets_[j], offsets_[j + 1] - offsets_[j]};
  }
  /// Total number of points over all rows.
  std::size_t total_points() const { return offsets_.back(); }
  /// Index of the first point of row j in points(); offsets()[M] == total_points().
  const std::vector<std::size_t>& offsets() const { return offsets_; }
  const std::vector<Point>& points() const { return points_; }
  void reserve(std::size_t points, std::size_t rows) {
    points_.reserve(points);
    offsets_.reserve(rows + 1);
  }

  /// Per-point weights (docs/seams.md), in the order of points(); empty: every weight 1 (and
  /// nothing stored). fit_surface() requires one finite weight > 0 per point.
  const std::vector<double>& weights() const { return weights_; }
  bool weighted() const { return !weights_.empty(); }
  void set_weights(std::vector<double> w) { weights_ = std::move(w); }
  /// Appends one weight (readers: in step with push_point()).
  void push_weight(double w) { weights_.push_back(w); }
  /// Row j's weights (empty when unweighted).
  std::span<const double> row_weights(std::size_t j) const {
    if (weights_.empty()) return {};
    return {weights_.data() + offsets_[j], offsets_[j + 1] - offsets_[j]};
  }

 private:
  std::vector<Point> points_;
  std::vector<std::size_t> offsets_;
  std::vector<double> weights_;
};

/// Axis-aligned bounding box of all points.
struct BoundingBox {
  Point min = Point::Constant(0.0);
  Point max = Point::Constant(0.0);
  double diagonal() const { return (max - min).norm(); }
};
BoundingBox bounding_box(const Rows& rows);

}  // namespace sfit
