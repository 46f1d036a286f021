// How far the points stray from the quadric through their neighbours (neighbour_noise.h).
#include "neighbour_noise.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <vector>

#include "between_rows.h"
#include "sfit/parametrization.h"

namespace sfit::detail {

namespace {

// Points predicted, at most; neighbours taken in the point's own row and in each other row.
constexpr long kQueries = 1024;
// The spread of jumps looks at every point of sets up to this size, at a stride above it.
constexpr long kSpreadQueries = 1L << 18;
constexpr int kOwnEachSide = 3;
constexpr int kOtherEachSide = 2;
constexpr int kRowsEachSide = 2;
// A quadric needs 6; with fewer than 10 neighbours one stray neighbour moves it too much.
constexpr std::size_t kLeastNeighbours = 10;
// The cubic (10 terms) is fitted too where there are at least this many.
constexpr long kCubicNeighbours = 16;
// Neighbours whose second principal axis is under this fraction of the first lie on a line:
// the quadric across it is not determined.
constexpr double kFlatSpread = 0.05;
// A jump: farther than this many T from the quadric through the neighbours. A surface smooth
// at the neighbours' scale and within T of each of them lies within about T of their quadric,
// so it misses a point beyond 2 T by more than T: only a knot line near it holds it (1 T would
// count noise within T, neighbours at -T and the point at +T).
constexpr double kJumpFactor = 2;

// Index k of a row of n points, wrapped where the row is closed, else -1 outside it.
long index_in(long k, long n, bool closed) {
  if (closed) return ((k % n) + n) % n;
  return k >= 0 && k < n ? k : -1;
}

// The point's miss over what T allows along the quadric's normal, or -1 where its neighbours
// cannot tell. `cubic`: the lesser of the quadric's miss and the cubic's (below).
double miss_over_t(const Point& q, const std::vector<Point>& nb, const Point& t, bool cubic) {
  if (nb.size() < kLeastNeighbours) return -1;
  Point c = Point::Zero();
  for (const Point& p : nb) c += p;
  c /= static_cast<double>(nb.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Point& p : nb) cov += (p - c) * (p - c).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  const Eigen::Vector3d lam = es.eigenvalues();  // ascending
  if (!(lam(2) > 0) || lam(1) < kFlatSpread * kFlatSpread * lam(2)) return -1;
  const Point n = es.eigenvectors().col(0), a1 = es.eigenvectors().col(2),
              a2 = es.eigenvectors().col(1);
  const double s1 = std::sqrt(lam(2) / static_cast<double>(nb.size())),
               s2 = std::sqrt(lam(1) / static_cast<double>(nb.size()));
  // The quadric's terms, then the cubic's.
  const auto row_of = [&](const Point& p) {
    const double s = (p - c).dot(a1) / s1, w = (p - c).dot(a2) / s2;
    Eigen::Matrix<double, 1, 10> r;
    r << 1, s, w, s * s, s * w, w * w, s * s * s, s * s * w, s * w * w, w * w * w;
    return r;
  };
  const long count = static_cast<long>(nb.size());
  Eigen::MatrixXd A(count, 10);
  Eigen::VectorXd h(count);
  for (long k = 0; k < count; ++k) {
    A.row(k) = row_of(nb[static_cast<std::size_t>(k)]);
    h(k) = (nb[static_cast<std::size_t>(k)] - c).dot(n);
  }
  const Eigen::Matrix<double, 1, 10> at = row_of(q);
  const double height = (q - c).dot(n);
  const auto miss_of = [&](long terms) {
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A.leftCols(terms));
    if (qr.rank() < terms) return -1.0;
    const Eigen::VectorXd coef = qr.solve(h);
    return std::abs(height - (at.leftCols(terms) * coef)(0));
  };
  double miss = miss_of(6);
  if (miss < 0) return -1;
  // Smooth data sampled sparsely at a small T: the quadric's own error (the third derivatives
  // times the spacing cubed) can exceed T where there is no noise (scan lines 0.04 apart at
  // 1e-5 of the diagonal: the median at 1.12 T, "T forces interpolation" on points that lie
  // exactly on a smooth height). The cubic through the same neighbours, where they determine
  // it, has the spacing to the fourth; noise misses both. A point strays by the lesser. (Not
  // for jumps, jump_spread(): a cubic bends through a step's neighbours more than a quadric,
  // and a LiDAR tile's roofs and trees at 1e-3 then no longer read as jumps everywhere.)
  if (cubic && count >= kCubicNeighbours) {
    const double cubic = miss_of(10);
    if (cubic >= 0) miss = std::min(miss, cubic);
  }
  const double allowed = n.cwiseAbs().dot(t);
  return allowed > 0 ? miss / allowed : -1;
}

// The miss over T of point j of row `row` against the quadric through its neighbours (-1 where
// they cannot tell); `nb` is scratch.
double point_ratio(const Rows& centred, const FitOptions& o, const Point& t, long row, long j,
                   std::vector<Point>& nb, bool cubic) {
  const long rows = static_cast<long>(centred.size());
  const auto own = centred[row];
  const long n = static_cast<long>(own.size());
  const Point& q = own[j];
  nb.clear();
  for (long d = -kOwnEachSide; d <= kOwnEachSide; ++d) {
    const long k = index_in(j + d, n, o.closed_u);
    if (d != 0 && k >= 0 && k != j) nb.push_back(own[k]);
  }
  for (long dr = -kRowsEachSide; dr <= kRowsEachSide; ++dr) {
    const long r = index_in(row + dr, rows, o.closed_v);
    if (dr == 0 || r < 0 || r == row) continue;
    const auto other = centred[r];
    const long m = static_cast<long>(other.size());
    if (m == 0) continue;
    const long near = static_cast<long>(nearest_in_row(other, q));
    for (long d = -kOtherEachSide; d <= kOtherEachSide; ++d) {
      // A closed row shorter than the window gives each point once.
      if (o.closed_u && 2 * kOtherEachSide + 1 > m && (d < 0 || d >= m)) continue;
      const long k = index_in(near + d, m, o.closed_u);
      if (k >= 0) nb.push_back(other[k]);
    }
  }
  return miss_over_t(q, nb, t, cubic);
}

// The point's miss, across its row, of the quadratic (in chord length) through up to
// kOwnEachSide points either side of it in its own row, over what T allows in that direction;
// -1 where a side has none or fewer than 4 neighbours are there. A jump within the row: a
// smooth row through dense points is followed closely by it whatever the spacing of the rows.
double row_miss_over_t(std::span<const Point> row, long j, bool closed, const Point& t) {
  const long n = static_cast<long>(row.size());
  double s[2 * kOwnEachSide];
  Point q[2 * kOwnEachSide];
  int count = 0, before = 0, after = 0;
  for (int side : {-1, 1}) {
    double at = 0;
    for (long d = 1; d <= kOwnEachSide; ++d) {
      const long k = index_in(j + side * d, n, closed),
                 prev = index_in(j + side * (d - 1), n, closed);
      if (k < 0 || k == j) break;
      at += (row[k] - row[prev]).norm();
      s[count] = side * at;
      q[count++] = row[k];
      (side < 0 ? before : after) += 1;
    }
  }
  if (before == 0 || after == 0 || count < 4) return -1;
  // x(s) = a + b s + c s^2 per axis, by least squares on the neighbours, s scaled to ~1.
  double scale = 0;
  for (int k = 0; k < count; ++k) scale = std::max(scale, std::abs(s[k]));
  if (!(scale > 0)) return -1;
  Eigen::Matrix<double, Eigen::Dynamic, 3> A(count, 3);
  Eigen::Matrix<double, Eigen::Dynamic, 3> B(count, 3);
  for (int k = 0; k < count; ++k) {
    const double w = s[k] / scale;
    A.row(k) << 1, w, w * w;
    B.row(k) = q[k].transpose();
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < 3) return -1;
  const Eigen::Matrix3d coef = qr.solve(Eigen::MatrixXd(B));  // rows: a, b, c
  // The point at the row's s = 0 (its own place), its tangent b, the miss across it.
  const Point m = row[j] - coef.row(0).transpose();
  const Point tangent = coef.row(1).transpose();
  const double tn = tangent.norm();
  const Point across = tn > 0 ? Point(m - m.dot(tangent / tn) * (tangent / tn)) : m;
  const double len = across.norm();
  if (!(len > 0)) return 0;
  const double allowed = (across / len).cwiseAbs().dot(t);
  return allowed > 0 ? len / allowed : -1;
}

Point allowed_t(const FitOptions& o, double roundoff) {
  Point t;
  for (int a = 0; a < 3; ++a) t[a] = o.tolerance[a] > 0 ? o.tolerance[a] : roundoff;
  return t;
}

}  // namespace

NeighbourNoise neighbour_noise(const Rows& centred, const FitOptions& o, double roundoff) {
  NeighbourNoise out;
  const long total = static_cast<long>(centred.total_points());
  if (total == 0) return out;
  const Point t = allowed_t(o, roundoff);
  const long stride = std::max<long>(1, total / kQueries);
  std::vector<double> ratios;
  std::vector<Point> nb;
  long row = 0;
  for (long g = stride / 2; g < total; g += stride) {
    while (static_cast<long>(centred.offsets()[row + 1]) <= g) ++row;
    const long j = g - static_cast<long>(centred.offsets()[row]);
    const double ratio = point_ratio(centred, o, t, row, j, nb, true);
    if (ratio < 0) continue;
    ratios.push_back(ratio);
    out.beyond += ratio > 1 ? 1 : 0;
  }
  out.points = static_cast<long>(ratios.size());
  if (ratios.empty()) return out;
  const auto mid = ratios.begin() + static_cast<long>(ratios.size() / 2);
  std::nth_element(ratios.begin(), mid, ratios.end());
  out.median = *mid;
  return out;
}

JumpSpread jump_spread(const Rows& centred, const FitOptions& o, double roundoff, double factor) {
  JumpSpread out;
  const long total = static_cast<long>(centred.total_points());
  const long rows = static_cast<long>(centred.size());
  if (total == 0) return out;
  const Point t = allowed_t(o, roundoff);
  const long stride = std::max<long>(1, total / kSpreadQueries);
  // Bins along a row: as many as the median row has points (a knot line per point at most).
  std::vector<long> lengths(static_cast<std::size_t>(rows));
  for (long r = 0; r < rows; ++r)
    lengths[static_cast<std::size_t>(r)] = static_cast<long>(centred[r].size());
  std::nth_element(lengths.begin(), lengths.begin() + rows / 2, lengths.end());
  out.bins = std::max<long>(1, lengths[static_cast<std::size_t>(rows / 2)]);
  out.rows = rows;
  std::vector<char> row_hit(static_cast<std::size_t>(rows), 0),
      bin_hit(static_cast<std::size_t>(out.bins), 0);
  std::vector<Point> nb;
  for (long r = 0; r < rows; ++r) {
    const auto row = centred[r];
    const long n = static_cast<long>(row.size());
    if (n == 0) continue;
    const long first = static_cast<long>(centred.offsets()[r]);
    // Where a jump lies along its row: its chord-length fraction (the row rules' u).
    std::vector<double> at;
    for (long g = first + (stride - first % stride) % stride; g < first + n; g += stride) {
      const long j = g - first;
      const double ratio = point_ratio(centred, o, t, r, j, nb, false);
      if (ratio < 0) continue;
      ++out.points;
      if (ratio <= factor || row_miss_over_t(row, j, o.closed_u, t) <= factor) continue;
      ++out.jumps;
      if (at.empty()) at = normalized_positions(row, Parametrization::kChord, o.closed_u);
      row_hit[static_cast<std::size_t>(r)] = 1;
      const long b = std::min(out.bins - 1, static_cast<long>(at[static_cast<std::size_t>(j)] *
                                                              static_cast<double>(out.bins)));
      bin_hit[static_cast<std::size_t>(std::max<long>(0, b))] = 1;
    }
  }
  out.rows_hit = std::count(row_hit.begin(), row_hit.end(), 1);
  out.bins_hit = std::count(bin_hit.begin(), bin_hit.end(), 1);
  return out;
}

bool neighbours_force_interpolation(const Rows& centred, const FitOptions& o, double roundoff,
                                    std::string& why) {
  const NeighbourNoise nn = neighbour_noise(centred, o, roundoff);
  if (nn.points == 0) {
    why = "no point has neighbours spread enough to tell its noise";
    return false;
  }
  char median[32];
  std::snprintf(median, sizeof median, "%.3g", nn.median);
  why = std::to_string(nn.beyond) + " of " + std::to_string(nn.points) +
        " points spread over the data lie farther than T from the quadric through their "
        "neighbours (the median at " +
        median + " T)";
  return nn.median > 1;
}

bool jumps_force_interpolation(const Rows& centred, const FitOptions& o, double roundoff,
                               std::string& why) {
  const JumpSpread js = jump_spread(centred, o, roundoff, kJumpFactor);
  if (js.points == 0 || js.jumps == 0) return false;
  const double rows_part = static_cast<double>(js.rows_hit) / static_cast<double>(js.rows);
  const double bins_part = static_cast<double>(js.bins_hit) / static_cast<double>(js.bins);
  if (2 * js.rows_hit < js.rows || 2 * js.bins_hit < js.bins) return false;
  char text[480];
  std::snprintf(text, sizeof text,
                "%ld of %ld points lie farther than 2 T from the quadric through their neighbours "
                "and from the curve through the neighbours in their row (jumps: no surface smooth "
                "there holds "
                "them), in %.0f %% of the rows and across %.0f %% of a row's length (%ld "
                "parts); a step or a spike needs knot lines on either side of it, along and "
                "across the rows, so jumps in half the rows and half a row's length need them "
                "about everywhere",
                js.jumps, js.points, 100 * rows_part, 100 * bins_part, js.bins);
  why = text;
  return true;
}

}  // namespace sfit::detail
