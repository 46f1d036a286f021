#include "mesh_fields.h"

#include <algorithm>
#include <cmath>

namespace sfit::exchange::detail {

namespace {

ScalarField clip(std::vector<double> values, std::size_t grid) {
  ScalarField f;
  std::vector<double> sorted;
  for (std::size_t k = 0; k < grid; ++k)
    if (std::isfinite(values[k])) sorted.push_back(values[k]);
  std::sort(sorted.begin(), sorted.end());
  if (!sorted.empty()) {
    const auto at = [&](double q) {
      return sorted[static_cast<std::size_t>(
          std::lround(q * static_cast<double>(sorted.size() - 1)))];
    };
    f.lo = at(kClipLow);
    f.hi = at(kClipHigh);
  }
  f.clipped.resize(values.size());
  for (std::size_t k = 0; k < values.size(); ++k)
    f.clipped[k] = std::isfinite(values[k]) ? std::clamp(values[k], f.lo, f.hi) : values[k];
  f.values = std::move(values);
  return f;
}

// Linear interpolation of y over non-decreasing x at t; `period` > 0 wraps (x in [0, period)).
Point interpolate(const std::vector<double>& x, const std::vector<Point>& y, std::size_t first,
                  std::size_t count, double t, double period) {
  if (count == 1) return y[first];
  const auto b = x.begin() + static_cast<std::ptrdiff_t>(first);
  const auto e = b + static_cast<std::ptrdiff_t>(count);
  const std::size_t hi = static_cast<std::size_t>(std::upper_bound(b, e, t) - b);
  if (hi == 0 || hi == count) {
    if (period <= 0) return y[first + (hi == 0 ? 0 : count - 1)];
    // Between the last point and the first one, a period later.
    const double x0 = x[first + count - 1], x1 = x[first] + period;
    const double tt = hi == 0 ? t + period : t;
    const double w = x1 > x0 ? (tt - x0) / (x1 - x0) : 0.0;
    return (1 - w) * y[first + count - 1] + w * y[first];
  }
  const double x0 = x[first + hi - 1], x1 = x[first + hi];
  const double w = x1 > x0 ? (t - x0) / (x1 - x0) : 0.0;
  return (1 - w) * y[first + hi - 1] + w * y[first + hi];
}

}  // namespace

CurvatureFields curvature_fields(const SurfaceFrame& f, const Mesh& m, const std::vector<double>& u,
                                 const std::vector<double>& v) {
  const std::size_t ng = m.vertices.size();
  std::vector<double> mean(ng + u.size()), gaussian(ng + u.size());
  const double sign = m.flipped ? -1.0 : 1.0;
  for (int b = 0; b < m.samples_v; ++b)
    for (int a = 0; a < m.samples_u; ++a) {
      const Curvature k = f.curvature(m.u[a], m.v[b]);
      mean[m.index(a, b)] = sign * k.mean;
      gaussian[m.index(a, b)] = k.gaussian;
    }
  for (std::size_t i = 0; i < u.size(); ++i) {
    const Curvature k = f.curvature(u[i], v[i]);
    mean[ng + i] = sign * k.mean;
    gaussian[ng + i] = k.gaussian;
  }
  return {clip(std::move(mean), ng), clip(std::move(gaussian), ng)};
}

DataPoints data_points(const Surface& s, const FitResult* fit, const Rows* rows) {
  DataPoints d;
  if (!fit || !rows || fit->u.size() != rows->total_points() || fit->v.size() != rows->size())
    return d;
  d.tolerance = fit->report.tolerance;
  d.points = rows->points();
  d.u = fit->u;
  d.v.resize(d.u.size());
  std::size_t k = 0;
  for (std::size_t j = 0; j < rows->size(); ++j)
    for (std::size_t i = 0; i < (*rows)[j].size(); ++i, ++k) d.v[k] = fit->point_v(j, k);
  d.deviation.resize(d.points.size());
  for (std::size_t i = 0; i < d.points.size(); ++i)
    d.deviation[i] = s.evaluate(d.u[i], d.v[i]) - d.points[i];
  return d;
}

std::vector<Point> grid_deviation(const Surface& s, const Mesh& m, const DataPoints& d,
                                  const Rows& rows) {
  std::vector<Point> out(m.vertices.size(), Point::Zero());
  if (d.points.empty()) return out;
  const double pu = m.periodic_u ? s.u_end() : 0.0;
  const double pv = m.periodic_v ? s.v_end() : 0.0;
  auto wrap = [](double t, double period) {
    return period > 0 ? t - period * std::floor(t / period) : t;
  };
  // Each row's points in increasing u (wrapped into the period), the rows in increasing v,
  // so the interpolation holds whatever order the data came in (a rotated closed row).
  const std::size_t nr = rows.size();
  std::vector<double> ru, rv;
  std::vector<Point> rdev, rvp;  // rvp: each point's v (in x), for points with their own v
  std::vector<std::size_t> first(nr), order(nr);
  for (std::size_t j = 0, k = 0; j < nr; k += rows[j].size(), ++j) {
    std::vector<std::size_t> idx(rows[j].size());
    for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = k + i;
    std::stable_sort(idx.begin(), idx.end(), [&](std::size_t x, std::size_t y) {
      return wrap(d.u[x], pu) < wrap(d.u[y], pu);
    });
    first[j] = ru.size();
    for (std::size_t i : idx) {
      ru.push_back(wrap(d.u[i], pu));
      rdev.push_back(d.deviation[i]);
      rvp.push_back(Point(wrap(d.v[i], pv), 0, 0));
    }
    rv.push_back(wrap(d.v[k], pv));
    order[j] = j;
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return rv[x] < rv[y]; });
  std::vector<double> v_sorted(nr);
  for (std::size_t j = 0; j < nr; ++j) v_sorted[j] = rv[order[j]];
  std::vector<Point> row_value(nr);
  // Points with their own v (parameters geometric, FitResult::v_points): each row's v at the
  // sample's u interpolated along the row as its values are, the rows ordered by it there.
  bool own_v = false;
  for (std::size_t j = 0, k = 0; j < nr && !own_v; k += rows[j].size(), ++j)
    for (std::size_t i = 1; i < rows[j].size(); ++i)
      if (d.v[k + i] != d.v[k]) own_v = true;
  std::vector<double> v_at(nr);
  std::vector<Point> value_at(nr);
  for (int a = 0; a < m.samples_u; ++a) {
    if (own_v) {
      for (std::size_t r = 0; r < nr; ++r) {
        v_at[r] = interpolate(ru, rvp, first[r], rows[r].size(), m.u[a], pu).x();
        value_at[r] = interpolate(ru, rdev, first[r], rows[r].size(), m.u[a], pu);
        order[r] = r;
      }
      std::stable_sort(order.begin(), order.end(),
                       [&](std::size_t x, std::size_t y) { return v_at[x] < v_at[y]; });
      for (std::size_t j = 0; j < nr; ++j) {
        v_sorted[j] = v_at[order[j]];
        row_value[j] = value_at[order[j]];
      }
    }
    for (std::size_t j = 0; j < nr && !own_v; ++j) {
      const std::size_t r = order[j];
      row_value[j] = interpolate(ru, rdev, first[r], rows[r].size(), m.u[a], pu);
    }
    for (int b = 0; b < m.samples_v; ++b)
      out[m.index(a, b)] = interpolate(v_sorted, row_value, 0, nr, m.v[b], pv);
  }
  return out;
}

double deviation_ratio(const Point& d, const Point& t) {
  double r = 0;
  for (int a = 0; a < 3; ++a) r = std::max(r, t[a] > 0 ? std::abs(d[a]) / t[a] : std::abs(d[a]));
  return r;
}

}  // namespace sfit::exchange::detail
