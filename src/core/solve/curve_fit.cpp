#include "sfit/curve_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <tuple>

#include "banded_lsq.h"
#include "basis.h"
#include "fit_monitor.h"
#include "parameters.h"
#include "sfit/error.h"
#include "thread_cache.h"

namespace sfit {

namespace {

// Positions (docs/method.md 7.4) whose factorisation has a pivot ratio min|R_ii| / max|R_ii| below
// this count as singular: the condition number is then above 100, and the curve may swing far
// between the points it fits. Measured (the pivot ratio of every factorisation of a fit at
// 1e-3): the paper's parameters never go below 0.28 on the shared data; chord length stays
// above 0.25 on evenly shaped sets but falls to 2e-12 on the topobathy grid, whose surface
// then reached 1e9 between data points of heights -1437 ... 2205.
constexpr double kMinPivotRatio = 1e-2;

// The data-independent part of one least-squares fit: parameters, basis values and the
// Givens factorisation with its rotation log (banded_lsq.h). Every row of the same length
// and every column of the transverse stage shares it for a given count (the trick of SISL's
// s1537: fit many curves of one parametrisation with one factorisation); fitting a curve is
// then a replay of the rotations on its points, bit-identical to factorising afresh.
struct Collocation {
  int degree, count, n_points;
  bool periodic;
  std::vector<double> positions;  // empty: the paper's parameters
  std::vector<double> t, basis;
  std::vector<int> first;
  detail::BandedLeastSquares lsq;
  bool singular = false;

  /// With `data`, factorises with it as right-hand side and records nothing (one use).
  Collocation(int p, int c, bool per, int n, std::span<const double> pos,
              const Point* data = nullptr, const double* weights = nullptr)
      : degree(p),
        count(c),
        n_points(n),
        periodic(per),
        positions(pos.begin(), pos.end()),
        lsq(c, p + 1, per) {
    const int w = p + 1;
    t = pos.empty() ? paper_parameters(p, c, per, n) : scaled_parameters(p, c, per, pos);
    basis.resize(static_cast<std::size_t>(n) * w);
    first.resize(static_cast<std::size_t>(n));
    if (!data) lsq.record_rotations();
    const Point zero = Point::Zero();
    for (int j = 0; j < n; ++j) {
      double* b = &basis[static_cast<std::size_t>(j) * w];
      first[j] = eval_basis(p, c, per, t[j], b);
      // Weighted least squares: equation j scaled by sqrt(w_j) (never on the shared path).
      lsq.add(first[j], b, data ? data[j] : zero, weights ? std::sqrt(weights[j]) : 1.0);
    }
    std::vector<Point> x;
    singular = !lsq.solve(x) || (!pos.empty() && lsq.pivot_ratio() < kMinPivotRatio);
  }
  std::size_t bytes() const {
    return sizeof(*this) + sizeof(double) * (positions.size() + t.size() + basis.size()) +
           sizeof(int) * first.size() + lsq.bytes();
  }
};

// FNV-1a over the positions' bits: part of the cache key (equality is checked on a hit).
std::uint64_t hash_positions(std::span<const double> pos) {
  std::uint64_t h = 1469598103934665603ull;
  for (double d : pos) {
    std::uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    h = (h ^ bits) * 1099511628211ull;
  }
  return h;
}

// Per-thread cache of collocations; rows too long to be worth caching, and rows whose
// positions no other curve shares, are factorised directly.
// 16 MiB per thread: with the persistent pool (parallel.h) every thread keeps its caches, and
// 64 MiB each took a 10^6-point fit at 1e-3 to 274 MB peak on 2 threads (16 MiB: 166 MB, and
// no slower: 0.85 s against 1.04 s wall for the whole run).
constexpr std::size_t kCacheBytes = std::size_t{16} << 20;
constexpr std::size_t kLongestCached = 1 << 17;
using CollocationKey = std::tuple<int, int, bool, int, std::uint64_t>;
thread_local detail::ThreadCache<CollocationKey, Collocation> cache(kCacheBytes);

// The cached collocation, or nullptr when the cached one was made for other positions (a
// hash collision).
const Collocation* collocation(int degree, int count, bool periodic, int n_points,
                               std::span<const double> positions) {
  const Collocation& C = cache.get(
      {degree, count, periodic, n_points, positions.empty() ? 0 : hash_positions(positions)},
      [&] { return std::make_unique<Collocation>(degree, count, periodic, n_points, positions); });
  if (!std::equal(C.positions.begin(), C.positions.end(), positions.begin(), positions.end()))
    return nullptr;
  return &C;
}

struct Workspace {
  std::vector<Point> control, z;
};
thread_local Workspace tls;

bool residuals(std::span<const Point> points, const Collocation& C, int count, int w,
               const Point* bound, const Workspace& ws, Point& max_dev);

enum class Solve { kFails, kHolds, kSingular };

// Least squares with `count` control points at the paper's parameters (or the positions')
// into ws.control. With `bound`, stops early (kFails) at the first point out of it; otherwise
// computes max_dev over all points. `used` is the collocation it used. A singular system is
// an internal error at the paper's parameters and kSingular at positions.
Solve solve_count(std::span<const Point> points, int degree, bool periodic, int count,
                  std::span<const double> positions, bool cache_it, const Point* bound,
                  Workspace& ws, Point& max_dev, const Collocation*& used,
                  std::unique_ptr<Collocation>& uncached, std::span<const double> weights = {}) {
  const int n_points = static_cast<int>(points.size());
  const int w = degree + 1;
  auto singular = [&]() {
    if (!positions.empty()) return Solve::kSingular;
    throw Error(
        ErrorCode::kInternal, "singular least-squares system in the curve stage", Place{},
        {static_cast<double>(degree), static_cast<double>(count), static_cast<double>(n_points)});
  };
  const Collocation* C = nullptr;
  if (cache_it && weights.empty() && static_cast<std::size_t>(n_points) <= kLongestCached)
    C = collocation(degree, count, periodic, n_points, positions);
  if (C) {
    used = C;
    if (C->singular || !C->lsq.replay(points.data(), ws.control, ws.z)) return singular();
  } else {
    // Too long to cache, or positions of this curve alone: factorise with the data directly
    // (no rotation log; the same bits as a replay).
    uncached =
        std::make_unique<Collocation>(degree, count, periodic, n_points, positions, points.data(),
                                      weights.empty() ? nullptr : weights.data());
    used = uncached.get();
    if (uncached->singular || !uncached->lsq.solve(ws.control)) return singular();
  }
  return residuals(points, *used, count, w, bound, ws, max_dev) ? Solve::kHolds : Solve::kFails;
}

bool residuals(std::span<const Point> points, const Collocation& C, int count, int w,
               const Point* bound, const Workspace& ws, Point& max_dev) {
  const int n_points = static_cast<int>(points.size());
  max_dev.setZero();
  const auto& P = ws.control;
  for (int j = 0; j < n_points; ++j) {
    const double* b = &C.basis[static_cast<std::size_t>(j) * w];
    const int f = C.first[j];
    Point c = Point::Zero();
    if (f + w <= count) {
      for (int i = 0; i < w; ++i) c += b[i] * P[f + i];
    } else {
      for (int i = 0; i < w; ++i) c += b[i] * P[wrap_index(f + i, count)];
    }
    const Point d = (c - points[j]).cwiseAbs();
    if (bound && !(d.array() <= bound->array()).all()) return false;
    max_dev = max_dev.cwiseMax(d);
  }
  return true;
}

CurveFit from_workspace(const Workspace& ws, const Collocation& C, const Point& max_dev) {
  CurveFit f;
  f.curve.degree = C.degree;
  f.curve.periodic = C.periodic;
  f.curve.control = ws.control;
  f.parameters = C.t;
  f.scaled = !C.positions.empty();
  f.max_deviation = max_dev;
  return f;
}

}  // namespace

CurveFit fit_curve_with_count(std::span<const Point> points, int degree, bool periodic, int count,
                              std::span<const double> positions, std::span<const double> weights) {
  Point dev;
  const Collocation* used = nullptr;
  std::unique_ptr<Collocation> uncached;
  if (solve_count(points, degree, periodic, count, positions, positions.empty(), nullptr, tls, dev,
                  used, uncached, weights) == Solve::kSingular)
    throw Error(ErrorCode::kInternal, "singular least-squares system in the curve stage", Place{},
                {static_cast<double>(degree), static_cast<double>(count),
                 static_cast<double>(points.size())});
  CurveFit f = from_workspace(tls, *used, dev);
  f.solves = 1;
  return f;
}

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
  Workspace& ws = tls;
  int solves = 0;
  CurveFit best;
  const bool cache_it = o.positions.empty() || o.shared_positions;
  // Does `count` hold? Keeps the fit when it does. The interpolant (count n) always holds: at
  // the positions if they give one within the bound, at the paper's parameters otherwise.
  auto holds = [&](int count) {
    detail::tick();  // a long row's search stops here when the fit is cancelled
    Point dev;
    ++solves;
    const Collocation* used = nullptr;
    std::unique_ptr<Collocation> uncached;
    const bool last_resort = count == n;
    Solve r = solve_count(points, o.degree, o.periodic, count, o.positions, cache_it,
                          last_resort && o.positions.empty() ? nullptr : &o.bound, ws, dev, used,
                          uncached, o.weights);
    if (last_resort && r != Solve::kHolds && !o.positions.empty()) {
      ++solves;
      r = solve_count(points, o.degree, o.periodic, count, {}, true, nullptr, ws, dev, used,
                      uncached);
    }
    const bool ok = r == Solve::kHolds;
    if (ok) best = from_workspace(ws, *used, dev);
    return ok;
  };
  auto finish = [&]() {
    best.solves = solves;
    return std::move(best);
  };
  if (o.search == CountSearch::kLinear) {
    for (int c = lo;; ++c) {
      if (o.linear_limit > 0 && c - lo >= o.linear_limit && c < n) {
        best = CurveFit{};  // no count up to here holds: no curve
        return finish();
      }
      if (holds(c)) return finish();
    }
  }
  const int start = o.hint > 0 ? std::clamp(o.hint, lo, n) : lo;
  bool start_holds;
  if (o.search == CountSearch::kKnown && o.hint > 0) {
    start_holds = holds(start);
    if (start_holds) return finish();
  } else {
    start_holds = holds(start);
  }
  // Bisect between a count that fails (bad) and one that holds (good; best has its fit).
  auto bisect = [&](int bad, int good) {
    while (good - bad > 1) {
      const int mid = bad + (good - bad) / 2;
      if (holds(mid)) {
        good = mid;
      } else {
        bad = mid;
      }
    }
    // best holds the fit of the last count that held, which is `good`.
    if (best.curve.count() != good) holds(good);
    return finish();
  };
  if (start_holds) {
    // Gallop down: start-1, start-2, start-4, ... until one fails.
    int good = start;
    for (int step = 1; good > lo; step *= 2) {
      const int c = std::max(lo, good - step);
      if (!holds(c)) return bisect(c, good);
      good = c;
    }
    return finish();
  }
  // Gallop up: start+1, start+2, start+4, ... until one holds (n always does).
  int bad = start;
  for (int step = 1;; step *= 2) {
    const int c = std::min(n, bad + step);
    if (holds(c)) return bisect(bad, c);
    bad = c;
  }
}

}  // namespace sfit
