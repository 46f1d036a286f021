#include "banded_lsq.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sfit::detail {

namespace {
// Applies the rotation that zeroes b against a: returns (c, s) with a := r.
inline void givens(double& a, double b, double& c, double& s) {
  // sqrt(a^2 + b^2), not std::hypot: 4x faster here and safe, because the fit works on
  // coordinates centred on their bounding box (no squares near overflow or underflow for
  // data within 1e-150 ... 1e150, which validate() enforces).
  const double r = std::sqrt(a * a + b * b);
  if (r == 0.0) {
    c = 1.0;
    s = 0.0;
    return;
  }
  c = a / r;
  s = b / r;
  a = r;
}
inline void rotate(double& x, double& y, double c, double s) {
  const double nx = c * x + s * y;
  y = -s * x + c * y;
  x = nx;
}
}  // namespace

BandedLeastSquares::BandedLeastSquares(int n, int width, bool periodic)
    : n_(n),
      w_(std::min(width, n)),
      tail_(periodic ? std::min(width, n) - 1 : 0),
      nb_(n - (periodic ? std::min(width, n) - 1 : 0)) {
  band_.assign(static_cast<std::size_t>(nb_) * w_, 0.0);
  side_.assign(static_cast<std::size_t>(nb_) * tail_, 0.0);
  tri_.assign(static_cast<std::size_t>(tail_) * tail_, 0.0);
  z_.assign(static_cast<std::size_t>(n_), Point::Zero());
  h_.assign(static_cast<std::size_t>(w_), 0.0);
  f_.assign(static_cast<std::size_t>(tail_), 0.0);
}

void BandedLeastSquares::reset() {
  std::fill(band_.begin(), band_.end(), 0.0);
  std::fill(side_.begin(), side_.end(), 0.0);
  std::fill(tri_.begin(), tri_.end(), 0.0);
  std::fill(z_.begin(), z_.end(), Point::Zero());
}

// add() for open problems of a fixed width: the same operations in the same order as the
// general path below (so the same bits), with the equation held in registers. The general
// path's scatter, modulo and window vector cost half the time of a chord-length curve fit
// (perf on a 10^5-point grid, which factorises every row afresh).
template <int W>
void BandedLeastSquares::add_open(int first, const double* coef, const Point& rhs, double weight) {
  double h[W];
  for (int i = 0; i < W; ++i) h[i] = 0.0 + weight * coef[i];  // as the scatter's 0 + a
  Point y = weight * rhs;
  for (int c = first; c < nb_; ++c) {
    const double hc = h[0];
    if (hc != 0.0) {
      double* R = &band_[static_cast<std::size_t>(c) * W];
      double cs, sn;
      givens(R[0], hc, cs, sn);
      for (int d = 1; d < W; ++d) rotate(R[d], h[d], cs, sn);
      for (int a = 0; a < 3; ++a) rotate(z_[c][a], y[a], cs, sn);
      if (recording_) log_.push_back({c, cs, sn});
    }
    bool any = false;
    for (int d = 0; d + 1 < W; ++d) {
      h[d] = h[d + 1];
      any = any || h[d] != 0.0;
    }
    h[W - 1] = 0.0;
    if (!any) break;
  }
  if (recording_) equation_end_.push_back(log_.size());
}

void BandedLeastSquares::add(int first, const double* coef, const Point& rhs, double weight) {
  if (tail_ == 0) {
    switch (w_) {
      case 2:
        return add_open<2>(first, coef, rhs, weight);
      case 3:
        return add_open<3>(first, coef, rhs, weight);
      case 4:
        return add_open<4>(first, coef, rhs, weight);
      case 5:
        return add_open<5>(first, coef, rhs, weight);
      case 6:
        return add_open<6>(first, coef, rhs, weight);
      default:
        break;
    }
  }
  // Scatter the equation into band part h (relative to band column c0) and tail part f.
  std::fill(h_.begin(), h_.end(), 0.0);
  std::fill(f_.begin(), f_.end(), 0.0);
  int c0 = -1;
  for (int i = 0; i < w_; ++i) {
    const int col = tail_ > 0 ? (first + i) % n_ : first + i;
    const double a = weight * coef[i];
    if (col < tail_) {
      f_[col] += a;
    } else {
      const int b = col - tail_;
      if (c0 < 0) c0 = b;
      h_[b - c0] += a;
    }
  }
  Point y = weight * rhs;
  // Band part: rotate against rows c0, c0+1, ... of R.
  if (c0 >= 0) {
    for (int c = c0; c < nb_; ++c) {
      const double hc = h_[0];
      if (hc != 0.0) {
        double* R = &band_[static_cast<std::size_t>(c) * w_];
        double cs, sn;
        givens(R[0], hc, cs, sn);
        for (int d = 1; d < w_; ++d) rotate(R[d], h_[d], cs, sn);
        double* S = tail_ ? &side_[static_cast<std::size_t>(c) * tail_] : nullptr;
        for (int t = 0; t < tail_; ++t) rotate(S[t], f_[t], cs, sn);
        for (int a = 0; a < 3; ++a) rotate(z_[c][a], y[a], cs, sn);
        if (recording_) log_.push_back({c, cs, sn});
      }
      // Shift the band window one column to the right.
      bool any = false;
      for (int d = 0; d + 1 < w_; ++d) {
        h_[d] = h_[d + 1];
        any = any || h_[d] != 0.0;
      }
      h_[w_ - 1] = 0.0;
      if (!any) break;
    }
  }
  // Tail part: a small dense upper triangle.
  for (int a = 0; a < tail_; ++a) {
    const double fa = f_[a];
    if (fa == 0.0) continue;
    double* T = &tri_[static_cast<std::size_t>(a) * tail_];
    double cs, sn;
    givens(T[a], fa, cs, sn);
    f_[a] = 0.0;
    for (int b = a + 1; b < tail_; ++b) rotate(T[b], f_[b], cs, sn);
    for (int k = 0; k < 3; ++k) rotate(z_[nb_ + a][k], y[k], cs, sn);
    if (recording_) log_.push_back({nb_ + a, cs, sn});
  }
  if (recording_) equation_end_.push_back(log_.size());
}

bool BandedLeastSquares::replay(const Point* rhs, std::vector<Point>& x,
                                std::vector<Point>& z) const {
  z.assign(static_cast<std::size_t>(n_), Point::Zero());
  std::size_t r = 0;
  for (std::size_t e = 0; e < equation_end_.size(); ++e) {
    Point y = 1.0 * rhs[e];  // add() scales by the weight, here 1
    for (; r < equation_end_[e]; ++r) {
      const Rotation& q = log_[r];
      for (int a = 0; a < 3; ++a) rotate(z[q.row][a], y[a], q.c, q.s);
    }
  }
  return back_substitute(z, x);
}

std::size_t BandedLeastSquares::bytes() const {
  return sizeof(*this) +
         sizeof(double) * (band_.size() + side_.size() + tri_.size() + h_.size() + f_.size()) +
         sizeof(Point) * z_.size() + sizeof(Rotation) * log_.capacity() +
         sizeof(std::size_t) * equation_end_.capacity();
}

double BandedLeastSquares::pivot_ratio() const {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (int c = 0; c < nb_; ++c) {
    lo = std::min(lo, std::abs(band_[static_cast<std::size_t>(c) * w_]));
    hi = std::max(hi, std::abs(band_[static_cast<std::size_t>(c) * w_]));
  }
  for (int a = 0; a < tail_; ++a) {
    lo = std::min(lo, std::abs(tri_[static_cast<std::size_t>(a) * tail_ + a]));
    hi = std::max(hi, std::abs(tri_[static_cast<std::size_t>(a) * tail_ + a]));
  }
  return hi > 0.0 ? lo / hi : 0.0;
}

bool BandedLeastSquares::solve(std::vector<Point>& x) const {
  return back_substitute(z_, x);
}

bool BandedLeastSquares::back_substitute(const std::vector<Point>& z, std::vector<Point>& x) const {
  double maxpiv = 0.0;
  for (int c = 0; c < nb_; ++c) maxpiv = std::max(maxpiv, std::abs(band_[c * w_]));
  for (int a = 0; a < tail_; ++a) maxpiv = std::max(maxpiv, std::abs(tri_[a * tail_ + a]));
  const double tiny = maxpiv * 1e-14;
  if (!(maxpiv > 0.0)) return false;
  // Without a tail the solution's order is the unknowns' order: solve straight into x (no
  // temporary; this runs once per solve of every count search).
  std::vector<Point> tmp;
  std::vector<Point>& sol = tail_ == 0 ? x : tmp;
  sol.resize(static_cast<std::size_t>(n_));
  // Tail unknowns (original columns 0 .. tail-1) sit at positions nb_ .. n_-1.
  for (int a = tail_ - 1; a >= 0; --a) {
    const double piv = tri_[a * tail_ + a];
    if (!(std::abs(piv) > tiny)) return false;
    Point s = z[nb_ + a];
    for (int b = a + 1; b < tail_; ++b) s -= tri_[a * tail_ + b] * sol[nb_ + b];
    sol[nb_ + a] = s / piv;
  }
  for (int c = nb_ - 1; c >= 0; --c) {
    const double* R = &band_[static_cast<std::size_t>(c) * w_];
    if (!(std::abs(R[0]) > tiny)) return false;
    Point s = z[c];
    for (int d = 1; d < w_ && c + d < nb_; ++d) s -= R[d] * sol[c + d];
    for (int t = 0; t < tail_; ++t) s -= side_[c * tail_ + t] * sol[nb_ + t];
    sol[c] = s / R[0];
  }
  if (tail_ == 0) return true;
  // Back to original column order.
  x.resize(static_cast<std::size_t>(n_));
  for (int col = 0; col < n_; ++col) x[col] = col < tail_ ? sol[nb_ + col] : sol[col - tail_];
  return true;
}

}  // namespace sfit::detail
