#include "geometric_params.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "parallel.h"

namespace sfit::detail {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// The centroid of a polyline's edges (each edge's midpoint weighted by its length), closed or
// open; the mean of the points where it has no length.
Vector3d edge_centroid(std::span<const Point> row, bool closed) {
  const std::size_t n = row.size();
  Vector3d sum = Vector3d::Zero(), mean = Vector3d::Zero();
  double total = 0;
  for (const Point& p : row) mean += p;
  mean /= static_cast<double>(std::max<std::size_t>(1, n));
  const std::size_t edges = closed ? n : n - 1;
  for (std::size_t k = 0; k < edges && n > 1; ++k) {
    const Point& a = row[k];
    const Point& b = row[(k + 1) % n];
    const double len = (b - a).norm();
    sum += 0.5 * len * (a + b);
    total += len;
  }
  return total > 0 ? Vector3d(sum / total) : mean;
}

// The unit normal of the best plane of a polyline (edges weighted by length about `c`), and
// whether the points span a plane at all.
bool plane_normal(std::span<const Point> row, const Vector3d& c, bool closed, Vector3d& n) {
  Matrix3d cov = Matrix3d::Zero();
  const std::size_t m = row.size(), edges = closed ? m : m - 1;
  for (std::size_t k = 0; k < edges && m > 1; ++k) {
    const Vector3d a = row[k] - c, b = row[(k + 1) % m] - c;
    const double len = (row[(k + 1) % m] - row[k]).norm();
    // The segment's second moment: len (a a^T + b b^T) / 3 + len (a b^T + b a^T) / 6.
    cov += len * ((a * a.transpose() + b * b.transpose()) / 3.0 +
                  (a * b.transpose() + b * a.transpose()) / 6.0);
  }
  Eigen::SelfAdjointEigenSolver<Matrix3d> es(cov);
  if (es.info() != Eigen::Success || !(es.eigenvalues()[1] > 0)) return false;
  n = es.eigenvectors().col(0);
  return true;
}

void scale_to_unit(std::vector<double>& x) {
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  const double a = *lo, span = *hi - *lo;
  for (double& t : x) t = span > 0 ? std::clamp((t - a) / span, 0.0, 1.0) : 0.0;
}

std::optional<Fractions> open_sheet(const Rows& rows, BasePlane plane) {
  const std::vector<Point>& pts = rows.points();
  const std::size_t n = pts.size();
  Vector3d c = Vector3d::Zero();
  for (const Point& p : pts) c += p;
  c /= static_cast<double>(n);
  Matrix3d cov = Matrix3d::Zero();
  for (const Point& p : pts) {
    const Vector3d d = p - c;
    cov += d * d.transpose();
  }
  Vector3d along = Vector3d::Zero();
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const auto r = rows[j];
    if (r.size() >= 2) along += r.back() - r.front();
  }
  const std::optional<SheetFrame> frame =
      sheet_frame(c, cov, along, edge_centroid(rows[0], false),
                  edge_centroid(rows[rows.size() - 1], false), plane);
  if (!frame) return std::nullopt;
  Fractions f;
  f.u.resize(n);
  f.v.resize(n);
  sheet_positions(*frame, pts, f.u, f.v);
  scale_to_unit(f.u);
  scale_to_unit(f.v);
  return f;
}

std::optional<Fractions> swept_axis(const Rows& rows) {
  const std::size_t M = rows.size();
  std::vector<Vector3d> c(M), nrm(M);
  for (std::size_t j = 0; j < M; ++j) {
    c[j] = edge_centroid(rows[j], true);
    if (!plane_normal(rows[j], c[j], true, nrm[j])) return std::nullopt;
  }
  // Orient the normals along the rows' order (or consistently, where the centroids coincide).
  const Vector3d path = c[M - 1] - c[0];
  if (path.norm() > 0 ? nrm[0].dot(path) < 0 : false) nrm[0] = -nrm[0];
  for (std::size_t j = 1; j < M; ++j)
    if (nrm[j].dot(nrm[j - 1]) < 0) nrm[j] = -nrm[j];
  // The reference direction: the first row's first point, carried from row to row.
  Vector3d e1 = rows[0][0] - c[0];
  Fractions f;
  const std::size_t n = rows.total_points();
  f.u.resize(n);
  f.v.resize(n);
  double s = 0;
  const auto& off = rows.offsets();
  constexpr double two_pi = 2 * std::numbers::pi;
  for (std::size_t j = 0; j < M; ++j) {
    if (j > 0) s += (c[j] - c[j - 1]).norm();
    e1 -= e1.dot(nrm[j]) * nrm[j];
    if (!(e1.norm() > 0)) return std::nullopt;
    e1.normalize();
    const Vector3d e2 = nrm[j].cross(e1);
    const auto row = rows[j];
    const std::size_t m = row.size();
    std::vector<double> angle(m);
    for (std::size_t k = 0; k < m; ++k) {
      const Vector3d d = row[k] - c[j];
      angle[k] = std::atan2(d.dot(e2), d.dot(e1));
      f.v[off[j] + k] = s + d.dot(nrm[j]);
    }
    // Does the angle turn one way, once round?
    double turn = 0;
    int forward = 0, backward = 0;
    for (std::size_t k = 0; k < m; ++k) {
      double d = angle[(k + 1) % m] - angle[k];
      if (d > std::numbers::pi) d -= two_pi;
      if (d < -std::numbers::pi) d += two_pi;
      turn += d;
      (d > 0 ? forward : backward) += 1;
    }
    const double sense = turn >= 0 ? 1.0 : -1.0;
    const bool monotone =
        (forward == 0 || backward == 0) && std::fabs(std::fabs(turn) - two_pi) < 1e-6;
    for (std::size_t k = 0; k < m; ++k) f.u[off[j] + k] = angle[k] / two_pi;
    if (!monotone) {
      // Chord length from the first point's angle, in the row's sense of turning.
      double total = 0;
      std::vector<double> at(m, 0.0);
      for (std::size_t k = 1; k <= m; ++k) {
        total += (row[k % m] - row[k - 1]).norm();
        if (k < m) at[k] = total;
      }
      for (std::size_t k = 0; k < m; ++k)
        f.u[off[j] + k] = angle[0] / two_pi + sense * (total > 0 ? at[k] / total : double(k) / m);
    }
    for (std::size_t k = 0; k < m; ++k) {
      double& t = f.u[off[j] + k];
      t -= std::floor(t);
      if (t >= 1) t = 0;
    }
  }
  scale_to_unit(f.v);
  return f;
}

}  // namespace

std::optional<SheetFrame> sheet_frame(const Point& mean, const Eigen::Matrix3d& cov, Point along,
                                      const Point& first, const Point& last, BasePlane plane) {
  Eigen::SelfAdjointEigenSolver<Matrix3d> es(cov);
  if (es.info() != Eigen::Success || !(es.eigenvalues()[1] > 0)) return std::nullopt;
  Vector3d normal = es.eigenvectors().col(0);
  if (plane == BasePlane::kAxis) {
    int axis = 0;
    normal.cwiseAbs().maxCoeff(&axis);
    const Vector3d e = Vector3d::Unit(axis);
    // The angle between the planes (sin of it: the normals' cross product).
    if (normal.cross(e).norm() < std::sin(kSamePlaneAngle)) return std::nullopt;
    normal = e;
  }
  along -= along.dot(normal) * normal;
  if (!(along.norm() > 0)) {
    along = es.eigenvectors().col(2);
    along -= along.dot(normal) * normal;  // (kBest: already in the plane)
    if (!(along.norm() > 0)) return std::nullopt;
  }
  along.normalize();
  Vector3d across = normal.cross(along);
  // v grows with the rows' order.
  if ((last - first).dot(across) < 0) across = -across;
  return SheetFrame{mean, along, across};
}

void sheet_positions(const SheetFrame& f, std::span<const Point> pts, std::span<double> u,
                     std::span<double> v) {
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const Vector3d d = pts[k] - f.c;
    u[k] = d.dot(f.along);
    v[k] = d.dot(f.across);
  }
}

std::optional<Fractions> base_surface_fractions(const Rows& rows, bool closed_u, bool closed_v,
                                                BasePlane plane) {
  if (rows.size() < 2 || closed_v || (closed_u && plane != BasePlane::kBest)) return std::nullopt;
  for (std::size_t j = 0; j < rows.size(); ++j)
    if (rows[j].empty()) return std::nullopt;
  return closed_u ? swept_axis(rows) : open_sheet(rows, plane);
}

void project_parameters(const Surface& s, const Rows& rows, std::vector<double>& u,
                        std::vector<double>& v, int steps, int threads) {
  const std::vector<Point>& pts = rows.points();
  const double ue = s.u_end(), ve = s.v_end();
  parallel_for((pts.size() + 4095) / 4096, threads, [&](std::size_t b) {
    for (std::size_t k = b * 4096; k < std::min(pts.size(), (b + 1) * 4096); ++k) {
      double a = u[k], c = v[k];
      for (int it = 0; it < steps; ++it) {
        Point d[6];
        s.derivatives(a, c, d);
        const Point r = d[0] - pts[k];
        const double g0 = r.dot(d[1]), g1 = r.dot(d[2]);
        const double h00 = d[1].squaredNorm(), h01 = d[1].dot(d[2]), h11 = d[2].squaredNorm();
        const double det = h00 * h11 - h01 * h01;
        if (!(det > 1e-14 * (h00 * h11)) || !(det > 0)) break;
        double du = -(h11 * g0 - h01 * g1) / det, dv = -(h00 * g1 - h01 * g0) / det;
        if (!std::isfinite(du) || !std::isfinite(dv)) break;
        du = std::clamp(du, -1.0, 1.0);
        dv = std::clamp(dv, -1.0, 1.0);
        const double na = a + du, nc = c + dv;
        // Accept only a step that brings the point nearer.
        const double before = r.squaredNorm();
        const auto put = [](double t, double end, bool closed) {
          if (closed) {
            t = std::fmod(t, end);
            if (t < 0) t += end;
            return t >= end ? 0.0 : t;
          }
          return std::clamp(t, 0.0, end);
        };
        const double pa = put(na, ue, s.periodic_u), pc = put(nc, ve, s.periodic_v);
        if (!((s.evaluate(pa, pc) - pts[k]).squaredNorm() < before)) break;
        a = pa;
        c = pc;
      }
      u[k] = a;
      v[k] = c;
    }
  });
}

}  // namespace sfit::detail
