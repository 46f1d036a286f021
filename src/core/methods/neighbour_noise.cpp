// How far the points stray from the quadric through their neighbours (neighbour_noise.h).
#include "neighbour_noise.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "between_rows.h"

namespace sfit::detail {

namespace {

// Points predicted, at most; neighbours taken in the point's own row and in each other row.
constexpr long kQueries = 1024;
constexpr int kOwnEachSide = 3;
constexpr int kOtherEachSide = 2;
constexpr int kRowsEachSide = 2;
// A quadric needs 6; with fewer than 10 neighbours one stray neighbour moves it too much.
constexpr std::size_t kLeastNeighbours = 10;
// Neighbours whose second principal axis is under this fraction of the first lie on a line:
// the quadric across it is not determined.
constexpr double kFlatSpread = 0.05;

// Index k of a row of n points, wrapped where the row is closed, else -1 outside it.
long index_in(long k, long n, bool closed) {
  if (closed) return ((k % n) + n) % n;
  return k >= 0 && k < n ? k : -1;
}

// The point's miss over what T allows along the quadric's normal, or -1 where its neighbours
// cannot tell.
double miss_over_t(const Point& q, const std::vector<Point>& nb, const Point& t) {
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
  const auto row_of = [&](const Point& p) {
    const double s = (p - c).dot(a1) / s1, w = (p - c).dot(a2) / s2;
    Eigen::Matrix<double, 1, 6> r;
    r << 1, s, w, s * s, s * w, w * w;
    return r;
  };
  Eigen::MatrixXd A(static_cast<long>(nb.size()), 6);
  Eigen::VectorXd h(static_cast<long>(nb.size()));
  for (std::size_t k = 0; k < nb.size(); ++k) {
    A.row(static_cast<long>(k)) = row_of(nb[k]);
    h(static_cast<long>(k)) = (nb[k] - c).dot(n);
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < 6) return -1;
  const Eigen::VectorXd coef = qr.solve(h);
  const double miss = std::abs((q - c).dot(n) - (row_of(q) * coef)(0));
  const double allowed = n.cwiseAbs().dot(t);
  return allowed > 0 ? miss / allowed : -1;
}

}  // namespace

NeighbourNoise neighbour_noise(const Rows& centred, const FitOptions& o, double roundoff) {
  NeighbourNoise out;
  const long total = static_cast<long>(centred.total_points());
  const long rows = static_cast<long>(centred.size());
  if (total == 0) return out;
  Point t;
  for (int a = 0; a < 3; ++a) t[a] = o.tolerance[a] > 0 ? o.tolerance[a] : roundoff;
  const long stride = std::max<long>(1, total / kQueries);
  std::vector<double> ratios;
  std::vector<Point> nb;
  long row = 0;
  for (long g = stride / 2; g < total; g += stride) {
    while (static_cast<long>(centred.offsets()[row + 1]) <= g) ++row;
    const auto own = centred[row];
    const long j = g - static_cast<long>(centred.offsets()[row]);
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
    const double ratio = miss_over_t(q, nb, t);
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

}  // namespace sfit::detail
