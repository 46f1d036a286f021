// Banded (and cyclic-banded) linear least squares by Givens rotations.
//
// PURPOSE  Solve min sum_r w_r^2 (a_r . x - b_r)^2 for x (n unknowns, three right-hand sides x,
//          y, z at once) where every equation a_r touches `width` consecutive unknowns
//          first .. first + width - 1, cyclically (mod n) when periodic.
// METHOD   Row-by-row Givens QR into an upper-triangular R of band width `width`, as Dierckx's
//          FITPACK does (fpcurf / fpperi). For periodic problems the first width-1 unknowns,
//          which the wrapped equations touch, are moved to a dense tail of R, so the wrap costs
//          O(width) extra per equation instead of a dense solve. Never forms the normal
//          equations, so the condition number is not squared: this matters at degree 20, where
//          banded Cholesky on B^T B (de Boor's BCHFAC, the paper's choice) loses ~12 digits.
// WHY OURS LAPACK has banded factorizations (dpbtrf, dgbtrf) but no banded least squares, and
//          Eigen's SparseQR is general-purpose: on a 1000-point cubic row this kernel is the
//          faster one (bench/bench_banded_lsq.cpp measures both).
#pragma once

#include <vector>

#include "sfit/rows.h"

namespace sfit::detail {

class BandedLeastSquares {
 public:
  /// n unknowns, `width` (= degree + 1) coefficients per equation, cyclic if periodic.
  BandedLeastSquares(int n, int width, bool periodic);
  void reset();
  /// Adds the equation w * (sum_i coef[i] x[(first + i) mod n]) = w * rhs.
  /// For accuracy with very different weights, add the heaviest equations first.
  void add(int first, const double* coef, const Point& rhs, double weight = 1.0);
  /// Back-substitution. Returns false when a pivot of R is (relatively) zero: the equations
  /// do not determine every unknown (Schoenberg-Whitney condition violated).
  bool solve(std::vector<Point>& x) const;

  /// Records every rotation add() applies to the right-hand side from now on, so that the
  /// same matrix can later be solved for other right-hand sides by replay(). The rotations
  /// depend on the matrix only; replaying them performs exactly the floating-point
  /// operations add() performed, so the results are bit-identical. Unit weights only.
  void record_rotations() { recording_ = true; }
  /// Solves for right-hand sides rhs[0 .. equations-1] (one per add(), in order) with the
  /// recorded rotations and the factor R. `z` is work space. Same return value as solve().
  bool replay(const Point* rhs, std::vector<Point>& x, std::vector<Point>& z) const;
  /// Smallest over largest |R_ii|: a cheap lower bound on 1 / condition number of the
  /// equations added so far (0 when a pivot is zero).
  double pivot_ratio() const;
  /// Bytes held (for caches).
  std::size_t bytes() const;

 private:
  int n_, w_, tail_, nb_;
  std::vector<double> band_;  // band_[c * w_ + d] = R(c, c + d), c < nb_
  std::vector<double> side_;  // side_[c * tail_ + t] = R(c, nb_ + t), c < nb_
  std::vector<double> tri_;   // tri_[a * tail_ + b] = R(nb_ + a, nb_ + b)
  std::vector<Point> z_;      // rotated right-hand sides, one per row of R
  // Work space for add().
  std::vector<double> h_, f_;
  // The rotation log of record_rotations(): row of R, cosine, sine; and the end of each
  // equation's rotations in it.
  struct Rotation {
    int row;
    double c, s;
  };
  bool recording_ = false;
  std::vector<Rotation> log_;
  std::vector<std::size_t> equation_end_;
  bool back_substitute(const std::vector<Point>& z, std::vector<Point>& x) const;
  template <int W>
  void add_open(int first, const double* coef, const Point& rhs, double weight);
};

}  // namespace sfit::detail
