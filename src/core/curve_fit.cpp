#include "sfit/curve_fit.h"

#include <algorithm>
#include <cmath>

#include "banded_lsq.h"
#include "sfit/basis.h"
#include "sfit/error.h"
#include "sfit/parametrization.h"

namespace sfit {

CurveFit fit_curve_with_count(std::span<const Point> points, int degree, bool periodic, int count) {
  const int n_points = static_cast<int>(points.size());
  CurveFit fit;
  fit.curve.degree = degree;
  fit.curve.periodic = periodic;
  fit.parameters = paper_parameters(degree, count, periodic, n_points);
  fit.solves = 1;
  const int w = degree + 1;
  std::vector<double> basis(static_cast<std::size_t>(n_points) * w);
  std::vector<int> first(static_cast<std::size_t>(n_points));
  detail::BandedLeastSquares lsq(count, w, periodic);
  for (int j = 0; j < n_points; ++j) {
    double* b = &basis[static_cast<std::size_t>(j) * w];
    first[j] = eval_basis(degree, count, periodic, fit.parameters[j], b);
    lsq.add(first[j], b, points[j]);
  }
  if (!lsq.solve(fit.curve.control))
    throw Error(
        ErrorCode::kInternal, "singular least-squares system in the curve stage", Place{},
        {static_cast<double>(degree), static_cast<double>(count), static_cast<double>(n_points)});
  const auto& P = fit.curve.control;
  for (int j = 0; j < n_points; ++j) {
    const double* b = &basis[static_cast<std::size_t>(j) * w];
    Point c = Point::Zero();
    for (int i = 0; i < w; ++i) c += b[i] * P[(first[j] + i) % count];
    fit.max_deviation = fit.max_deviation.cwiseMax((c - points[j]).cwiseAbs());
  }
  return fit;
}

namespace {

bool holds(const CurveFit& f, const Point& bound) {
  return (f.max_deviation.array() <= bound.array()).all();
}

}  // namespace

CurveFit fit_curve(std::span<const Point> points, const CurveFitOptions& o) {
  const int n = static_cast<int>(points.size());
  if (n == 0) throw Error(ErrorCode::kInputData, "a row has no points");
  if (n == 1) {
    CurveFit pole;
    pole.curve.degree = 0;
    pole.curve.periodic = false;
    pole.curve.control = {points[0]};
    pole.parameters = {0.0};
    return pole;
  }
  if (n < o.degree + 1) {
    // The paper's order-N interpolant of a short row.
    CurveFit f = fit_curve_with_count(points, n - 1, o.periodic, n);
    f.max_deviation.setZero();  // interpolation: the residual is round-off
    return f;
  }
  const int lo = o.degree + 1;
  int solves = 0;
  auto try_count = [&](int count) {
    CurveFit f = fit_curve_with_count(points, o.degree, o.periodic, count);
    ++solves;
    return f;
  };
  auto finish = [&](CurveFit f) {
    f.solves = solves;
    return f;
  };
  if (o.search == CountSearch::kLinear) {
    for (int c = lo; c < n; ++c) {
      CurveFit f = try_count(c);
      if (holds(f, o.bound)) return finish(std::move(f));
    }
    return finish(try_count(n));
  }
  // Fast: gallop upward from lo, then bisect between the last failing and first holding count.
  CurveFit best = try_count(lo);
  if (holds(best, o.bound)) return finish(std::move(best));
  int bad = lo, step = 1;
  int good = -1;
  while (true) {
    const int c = std::min(n, lo + step);
    if (c == n) {
      good = n;
      best = try_count(n);
      break;
    }
    CurveFit f = try_count(c);
    if (holds(f, o.bound)) {
      good = c;
      best = std::move(f);
      break;
    }
    bad = c;
    step *= 2;
  }
  auto bisect = [&](int bad_count, int good_count) {
    while (good_count - bad_count > 1) {
      const int mid = bad_count + (good_count - bad_count) / 2;
      CurveFit f = try_count(mid);
      if (holds(f, o.bound)) {
        good_count = mid;
        best = std::move(f);
      } else {
        bad_count = mid;
      }
    }
    return good_count;
  };
  good = bisect(bad, good);
  // Feasibility is not strictly monotone in the count: look a few counts further down so the
  // result agrees with the paper's linear search where a lower count also holds.
  constexpr int kDownwardCheck = 3;
  for (int c = good - 2; c >= std::max(lo + 1, good - 1 - kDownwardCheck); --c) {
    CurveFit f = try_count(c);
    if (holds(f, o.bound)) {
      best = std::move(f);
      good = bisect(lo, c);
      c = good - 1;  // continue below the new answer
    }
  }
  return finish(std::move(best));
}

}  // namespace sfit
