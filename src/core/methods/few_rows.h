// The surface search with fewer rows than the degree across needs (surface_method.cpp).
// Private to the surface method.
#pragma once

#include <cstddef>
#include <optional>

#include "sfit/surface.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

// Fewer rows than degree_v + 1, open across: no least-squares fit of that degree across them.
// The search then fits at degree M - 1 across (nv = M, through the rows' direction as the two
// stages' columns go) and raises each surface exactly to degree_v (nv = degree_v + 1, the
// two stages' shape), so its pairs, its bound and its result count the surface it returns.
class FewRows {
 public:
  FewRows(std::size_t rows, const FitOptions& o) {
    if (!o.closed_v && rows >= 2 && rows < static_cast<std::size_t>(o.degree_v) + 1) {
      rows_ = static_cast<int>(rows);
      degree_ = o.degree_v;
    }
  }
  /// The options the search's problems are made with.
  FitOptions options(FitOptions o) const {
    if (degree_ > 0) o.degree_v = rows_ - 1;
    return o;
  }
  /// The problem's nv for the surface's nv.
  int nv(int n) const { return degree_ > 0 ? rows_ : n; }
  int min_v(int problem) const { return degree_ > 0 ? degree_ + 1 : problem; }
  int max_v(int problem) const { return degree_ > 0 ? degree_ + 1 : problem; }
  /// The problem's surface raised to degree_v across (degree elevation of the one Bezier
  /// segment across: the same surface).
  std::optional<Surface> raise(std::optional<Surface> s) const {
    if (degree_ == 0 || !s) return s;
    while (s->degree_v < degree_) {
      const int p = s->degree_v;
      Surface e = *s;
      e.degree_v = p + 1;
      e.count_v = p + 2;
      e.control.assign(static_cast<std::size_t>(e.count_u) * e.count_v, Point::Zero());
      for (int i = 0; i < e.count_u; ++i) {
        e.at(i, 0) = s->at(i, 0);
        e.at(i, p + 1) = s->at(i, p);
        for (int k = 1; k <= p; ++k) {
          const double a = static_cast<double>(k) / (p + 1);
          e.at(i, k) = a * s->at(i, k - 1) + (1 - a) * s->at(i, k);
        }
      }
      s = std::move(e);
    }
    return s;
  }

 private:
  int rows_ = 0, degree_ = 0;  // degree_ 0: as many rows as the degree needs
};

}  // namespace sfit::detail
