#include "sfit/render/deviations.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "nearest.h"
#include "sfit/error.h"

namespace sfit::render {

std::vector<Point> deviations_at_parameters(const Surface& s, const Rows& rows,
                                            std::span<const double> u, std::span<const double> v) {
  // v per row, or per point (FitResult::v_for_points(): Parametrization::kGeometric).
  const bool per_point = v.size() != rows.size();
  if (u.size() != rows.total_points() || (per_point && v.size() != rows.total_points()))
    throw Error(ErrorCode::kInternal,
                "deviations_at_parameters: parameter counts differ from the data", Place{},
                {static_cast<double>(u.size()), static_cast<double>(v.size())});
  std::vector<Point> d(rows.total_points());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const std::size_t first = rows.offsets()[j];
    const auto row = rows[j];
    for (std::size_t k = 0; k < row.size(); ++k)
      d[first + k] = s.evaluate(u[first + k], per_point ? v[first + k] : v[j]) - row[k];
  }
  return d;
}

double tolerance_ratio(const Point& d, const Point& t, double zero_scale) {
  double r = 0;
  for (int a = 0; a < 3; ++a) {
    const double scale = t[a] > 0 ? t[a] : zero_scale;
    if (scale > 0) r = std::max(r, std::abs(d[a]) / scale);
  }
  return r;
}

namespace {

double wrap_or_clamp(double t, double end, bool periodic) {
  if (periodic) {
    t = std::fmod(t, end);
    return t < 0 ? t + end : t;
  }
  return std::clamp(t, 0.0, end);
}

// Newton's method on f(u, v) = |S(u, v) - q|^2 / 2 with a backtracking line search. An open
// direction at its end whose gradient points out of the domain is held there (projected
// Newton), so points beyond an edge converge onto it.
ClosestPoint refine(const Surface& s, const Point& q, double u, double v) {
  const double ue = s.u_end(), ve = s.v_end();
  Point d[6];
  s.derivatives(u, v, d);
  double f = (d[0] - q).squaredNorm();
  for (int it = 0; it < 40; ++it) {
    const Point r = d[0] - q;
    const Eigen::Vector2d g(d[1].dot(r), d[2].dot(r));
    Eigen::Matrix2d h;
    h << d[1].dot(d[1]) + d[3].dot(r), d[1].dot(d[2]) + d[4].dot(r), d[1].dot(d[2]) + d[4].dot(r),
        d[2].dot(d[2]) + d[5].dot(r);
    if (!(h(0, 0) > 0 && h(1, 1) > 0 && h.determinant() > 0)) {  // not convex here: Gauss-Newton
      h << d[1].dot(d[1]), d[1].dot(d[2]), d[1].dot(d[2]), d[2].dot(d[2]);
      h.diagonal().array() += 1e-12 * (h.trace() + 1e-300);
    }
    const bool hold_u = !s.periodic_u && ((u <= 0 && g.x() > 0) || (u >= ue && g.x() < 0));
    const bool hold_v = !s.periodic_v && ((v <= 0 && g.y() > 0) || (v >= ve && g.y() < 0));
    Eigen::Vector2d step;
    if (hold_u && hold_v) break;
    if (hold_u)
      step = {0, -g.y() / h(1, 1)};
    else if (hold_v)
      step = {-g.x() / h(0, 0), 0};
    else
      step = -h.ldlt().solve(g);
    if (!step.allFinite()) break;
    bool moved = false;
    for (int k = 0; k < 20; ++k, step *= 0.5) {
      const double nu = wrap_or_clamp(u + step.x(), ue, s.periodic_u);
      const double nv = wrap_or_clamp(v + step.y(), ve, s.periodic_v);
      const double nf = (s.evaluate(nu, nv) - q).squaredNorm();
      if (nf < f) {
        moved = std::abs(nu - u) > 1e-14 * (1 + ue) || std::abs(nv - v) > 1e-14 * (1 + ve);
        u = nu;
        v = nv;
        f = nf;
        break;
      }
    }
    if (!moved) break;
    s.derivatives(u, v, d);
  }
  return {u, v, s.evaluate(u, v) - q};
}

}  // namespace

std::vector<ClosestPoint> closest_points(const Surface& s, std::span<const Point> points) {
  if (points.empty()) return {};
  constexpr std::size_t kStarts = 6;
  const double ue = s.u_end(), ve = s.v_end();
  // Samples about evenly spaced on the surface (the control polygons' lengths tell how long
  // it is each way), some 250,000 of them, and at least 4 a knot span.
  double len_u = 0, len_v = 0;
  for (int j = 0; j < s.count_v; ++j) {
    double l = 0;
    for (int i = 0; i + 1 < s.full_count_u(); ++i)
      l += (s.full_at(i + 1, j) - s.full_at(i, j)).norm();
    len_u = std::max(len_u, l);
  }
  for (int i = 0; i < s.count_u; ++i) {
    double l = 0;
    for (int j = 0; j + 1 < s.full_count_v(); ++j)
      l += (s.full_at(i, j + 1) - s.full_at(i, j)).norm();
    len_v = std::max(len_v, l);
  }
  const double h = std::sqrt(std::max(len_u * len_v, 1e-300) / 250000.0);
  auto count = [h](double len, double end) {
    const double by_length = len > 0 && h > 0 ? len / h : 0;
    return static_cast<int>(std::clamp(std::max(by_length, 4 * std::ceil(end)), 16.0, 4000.0));
  };
  const int gu = count(len_u, ue), gv = count(len_v, ve);
  std::vector<Point> samples;
  std::vector<std::pair<double, double>> params;
  samples.reserve(static_cast<std::size_t>(gu + 1) * (gv + 1));
  for (int i = 0; i <= gu; ++i)
    for (int j = 0; j <= gv; ++j) {
      const double u = ue * i / gu, v = ve * j / gv;
      samples.push_back(s.evaluate(u, v));
      params.emplace_back(u, v);
    }
  const detail::NearestPoint grid(std::move(samples));
  std::vector<ClosestPoint> out(points.size());
  // Several starts: on a thin part (a trailing edge) the nearest sample may lie on the far side.
  for (std::size_t k = 0; k < points.size(); ++k) {
    bool first = true;
    for (std::size_t i : grid.k_nearest(points[k], kStarts)) {
      const ClosestPoint c = refine(s, points[k], params[i].first, params[i].second);
      if (first || c.deviation.squaredNorm() < out[k].deviation.squaredNorm()) out[k] = c;
      first = false;
    }
  }
  return out;
}

std::vector<double> row_parameters(const Surface& s, const Rows& rows,
                                   std::span<const ClosestPoint> closest) {
  std::vector<double> v(rows.size());
  const double ve = s.v_end();
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const std::size_t first = rows.offsets()[j], n = rows[j].size();
    std::vector<double> vs;
    for (std::size_t k = 0; k < n; ++k) {
      double x = closest[first + k].v;
      if (s.periodic_v) {  // unwrap around the first point's v
        const double ref = closest[first].v;
        while (x - ref > ve / 2) x -= ve;
        while (ref - x > ve / 2) x += ve;
      }
      vs.push_back(x);
    }
    std::nth_element(vs.begin(), vs.begin() + vs.size() / 2, vs.end());
    v[j] = wrap_or_clamp(vs[vs.size() / 2], ve, s.periodic_v);
  }
  return v;
}

}  // namespace sfit::render
