// The knots of one direction of a Surface: uniform (the default) or any non-decreasing vector
// with multiplicities (docs/surface-json.md, docs/method.md section 2).
#pragma once

#include <span>
#include <string>
#include <vector>

namespace sfit {

/// Knots of a B-spline direction of `degree` with `count` distinct control points.
///
/// Default-constructed, a KnotVector is *uniform*: the knots of knots.h, which every surface
/// sfit fitted before non-uniform knots had (clamped integers 0 ... count - degree when open,
/// the integers i - degree when periodic). It then stores nothing, and the owner's degree,
/// count and periodic flag say everything; evaluation takes the fast uniform path.
///
/// A non-uniform KnotVector holds the full vector in the contract's layout: count + degree + 1
/// knots when open (degree + 1 equal knots at each end), count + 2 degree + 1 when periodic
/// (the spacing repeats with the period knots[degree + count] - knots[degree]). The domain
/// begins at 0: [knots[degree], knots[count]] = [0, end()] open, [0, end()) periodic. Interior
/// knots may repeat up to `degree` times (a corner: C^0 at multiplicity degree). A vector that
/// equals the uniform one (within 1e-9 relative) is stored as uniform, so the same surface
/// always takes the same path and gives the same bits.
class KnotVector {
 public:
  KnotVector() = default;

  /// The full vector, validated (Error kInputData naming `what` and the offending entry).
  static KnotVector from_full(int degree, bool periodic, std::vector<double> full,
                              const std::string& what = "knots");
  /// From distinct breakpoints 0 = b_0 < b_1 < ... < b_m = end and multiplicities: open,
  /// `mults` has one entry per interior breakpoint b_1 ... b_{m-1}; periodic, one per b_0 ...
  /// b_{m-1} (the period is b_m). Empty `mults` means every multiplicity 1.
  static KnotVector from_breaks(int degree, bool periodic, std::span<const double> breaks,
                                std::span<const int> mults = {});

  bool uniform() const { return full_.empty(); }
  int degree() const { return degree_; }
  bool periodic() const { return periodic_; }
  /// Distinct control points (a non-uniform vector only; a uniform one knows none).
  int count() const { return count_; }
  /// The full vector of a non-uniform KnotVector (empty when uniform).
  const std::vector<double>& full() const { return full_; }
  /// End of the domain [0, end()] (non-uniform only).
  double end() const { return end_; }
  /// The distinct knots of the domain [0, end()] (with both ends) and their multiplicities
  /// within the full vector (ends of an open vector: degree + 1).
  void breaks(std::vector<double>& values, std::vector<int>& mults) const;

  /// Index s of the span [full[s], full[s+1]) holding t (a non-empty span: degree <= s <
  /// count open, degree <= s < degree + count periodic) after clamping t into an open domain or
  /// wrapping it around a periodic one (t is changed to the reduced value; NaN reads as 0).
  int find_span(double& t) const;

  friend bool operator==(const KnotVector& a, const KnotVector& b) {
    return a.full_ == b.full_ &&
           (a.uniform() || (a.degree_ == b.degree_ && a.periodic_ == b.periodic_));
  }

 private:
  int degree_ = 0;
  bool periodic_ = false;
  int count_ = 0;
  double end_ = 0;
  std::vector<double> full_;
};

/// The full vector of one direction: `k`'s own when non-uniform, else the uniform vector of
/// degree and count (knots.h).
std::vector<double> full_knots(const KnotVector& k, int degree, int count, bool periodic);

}  // namespace sfit
