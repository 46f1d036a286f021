#include "rerepresent.h"

#include <algorithm>
#include <array>
#include <memory>
#include <numeric>
#include <optional>
#include <tuple>

#include "banded_lsq.h"
#include "basis.h"
#include "parameters.h"
#include "thread_cache.h"

namespace sfit {
namespace {

// What a re-representation needs that does not depend on the control points: the data's new
// parameters and basis values there, the old basis at the sample parameters tau_l, the new
// basis at the Greville abscissae g_l and the factorised interpolation at them. Rows of one
// length and count (and all columns) share it.
struct Geometry {
  std::vector<double> old_t;  // the old parameters it was made for
  std::vector<double> params, db, sb, gb;
  std::vector<int> dfirst, sfirst, gfirst;
  detail::BandedLeastSquares interp;
  bool singular = false;

  Geometry(const CurveFit& fit, std::size_t n_data, int degree, int count, bool periodic,
           std::span<const double> target, const std::vector<double>* samples = nullptr)
      : old_t(fit.parameters), interp(count, degree + 1, periodic) {
    const Curve& old = fit.curve;
    const int w = degree + 1, wo = old.degree + 1;
    const ReparameterMap map(old.degree, old.count(), degree, count, periodic, fit.scaled);
    // Arc-length samples (open curves): the data map piecewise linearly from them.
    const std::vector<double>& tau = samples ? *samples : map.samples();
    const auto& g = map.targets();
    auto image = [&](double t) {
      if (!samples) return map(t);
      if (t <= tau.front()) return g.front();
      if (t >= tau.back()) return g.back();
      const std::size_t l =
          static_cast<std::size_t>(std::upper_bound(tau.begin(), tau.end(), t) - tau.begin()) - 1;
      const double d = tau[l + 1] - tau[l];
      return g[l] + (d > 0 ? (t - tau[l]) / d : 0.0) * (g[l + 1] - g[l]);
    };
    if (target.empty()) {
      params.resize(n_data);
      for (std::size_t k = 0; k < n_data; ++k) params[k] = image(fit.parameters[k]);
    } else {
      params.assign(target.begin(), target.end());
    }
    db.resize(n_data * w);
    dfirst.resize(n_data);
    for (std::size_t k = 0; k < n_data; ++k)
      dfirst[k] = eval_basis(degree, count, periodic, params[k], &db[k * w]);
    sb.resize(static_cast<std::size_t>(count) * wo);
    sfirst.resize(static_cast<std::size_t>(count));
    gb.resize(static_cast<std::size_t>(count) * w);
    gfirst.resize(static_cast<std::size_t>(count));
    interp.record_rotations();
    for (int l = 0; l < count; ++l) {
      sfirst[l] = eval_basis(old.degree, old.count(), old.periodic, tau[l],
                             &sb[static_cast<std::size_t>(l) * wo]);
      gfirst[l] = eval_basis(degree, count, periodic, g[l], &gb[static_cast<std::size_t>(l) * w]);
      interp.add(gfirst[l], &gb[static_cast<std::size_t>(l) * w], Point::Zero());
    }
    std::vector<Point> x;
    singular = !interp.solve(x);
  }
  std::size_t bytes() const {
    return sizeof(*this) +
           sizeof(double) * (old_t.size() + params.size() + db.size() + sb.size() + gb.size()) +
           sizeof(int) * (dfirst.size() + sfirst.size() + gfirst.size()) + interp.bytes();
  }
};

using GeometryKey = std::tuple<int, int, bool, int, int, std::size_t, bool, bool>;
// 16 MiB per thread, as curve_fit.cpp's collocations.
thread_local detail::ThreadCache<GeometryKey, Geometry> geometries(std::size_t{16} << 20);

// The cached geometry when it was made for the same old parameters and target; a fresh one
// (in `uncached`) otherwise, e.g. for a caller's own parameters.
const Geometry& geometry(const CurveFit& fit, std::size_t n_data, int degree, int count,
                         bool periodic, std::span<const double> target,
                         std::unique_ptr<Geometry>& uncached) {
  const Curve& old = fit.curve;
  const GeometryKey key{old.degree, old.count(), periodic,        degree,
                        count,      n_data,      !target.empty(), fit.scaled};
  const Geometry& G = geometries.get(key, [&] {
    return std::make_unique<Geometry>(fit, n_data, degree, count, periodic, target);
  });
  const bool same_old = G.old_t == fit.parameters;
  const bool same_target =
      target.empty() || std::equal(target.begin(), target.end(), G.params.begin(), G.params.end());
  if (same_old && same_target) return G;
  uncached = std::make_unique<Geometry>(fit, n_data, degree, count, periodic, target);
  return *uncached;
}

// The paper's sample parameters moved to equal arc length: sample l at the point whose arc
// length from the start is tau_l / tau_last of the whole (dense chords, 32 per old span).
std::vector<double> arc_length_samples(const Curve& old, const std::vector<double>& tau) {
  const double end = old.domain_end();
  const int n = 32 * std::max(1, old.count() - old.degree);
  std::vector<double> t(n + 1), s(n + 1, 0.0);
  Point prev = old.evaluate(0);
  for (int i = 0; i <= n; ++i) {
    t[i] = end * i / n;
    const Point p = old.evaluate(t[i]);
    if (i > 0) s[i] = s[i - 1] + (p - prev).norm();
    prev = p;
  }
  std::vector<double> out(tau.size());
  if (!(s[n] > 0) || tau.size() < 2) return tau;
  for (std::size_t l = 0; l < tau.size(); ++l) {
    const double want = s[n] * (tau[l] - tau.front()) / (tau.back() - tau.front());
    const std::size_t i = std::min<std::size_t>(
        n - 1, static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), want) - s.begin()) -
                   (want > 0 ? 1 : 0));
    const double d = s[i + 1] - s[i];
    out[l] = t[i] + (d > 0 ? (want - s[i]) / d : 0.0) * (t[i + 1] - t[i]);
  }
  out.front() = tau.front();
  out.back() = tau.back();
  return out;
}

// The repair rounds' equations (weighted data points, then the samples) go into the banded QR
// heaviest first up to this many control points, in the order of their first unknown above it.
// Row-by-row Givens QR keeps an equation's fill-in within the band only while the rows of R
// after its first unknown are still empty; an equation added behind rows that exist further on
// rotates against each of them until its fill-in dies out. Heaviest first (weights in no
// relation to position) therefore costs up to O(count) per equation, O(count^2) a round: a
// column of 20,000 rows of 2-3 points spent 55 % of its fit there (thousands of rotations per
// equation). The position order costs O(width^2) per equation but rounds differently, so below
// the threshold the heaviest-first order (and every recorded result) is kept.
constexpr int kHeaviestFirstUpTo = 4096;

}  // namespace

std::string_view to_string(Resampling r) {
  return r == Resampling::kArcLength ? "arc_length" : "paper";
}
bool parse_resampling(std::string_view name, Resampling& out) {
  if (name == "paper") {
    out = Resampling::kPaper;
  } else if (name == "arc_length") {
    out = Resampling::kArcLength;
  } else {
    return false;
  }
  return true;
}

Rerepresentation rerepresent(const CurveFit& fit, std::span<const Point> data, int degree,
                             int count, bool periodic, const Point& bound,
                             std::span<const double> target_parameters, Resampling resampling) {
  Rerepresentation out;
  out.curve.degree = degree;
  out.curve.periodic = periodic;
  const std::size_t n_data = data.size();
  const Curve& old = fit.curve;

  if (old.degree == 0) {  // pole: every control point is the single point
    out.curve.control.assign(static_cast<std::size_t>(count), old.control[0]);
    out.parameters.assign(n_data, 0.0);
    if (!target_parameters.empty())
      out.parameters.assign(target_parameters.begin(), target_parameters.end());
    for (std::size_t k = 0; k < n_data; ++k)
      out.max_deviation = out.max_deviation.cwiseMax((old.control[0] - data[k]).cwiseAbs());
    out.holds = (out.max_deviation.array() <= bound.array()).all();
    return out;
  }

  // Same degree and count: the re-representation is the curve itself (ReparameterMap is the
  // identity and interpolating its own samples returns it), so skip the work.
  if (old.degree == degree && old.count() == count && old.periodic == periodic &&
      (target_parameters.empty() || std::equal(target_parameters.begin(), target_parameters.end(),
                                               fit.parameters.begin(), fit.parameters.end()))) {
    out.curve = old;
    out.parameters = fit.parameters;
    out.max_deviation = fit.max_deviation;  // measured at these parameters by the curve stage
    out.holds = (out.max_deviation.array() <= bound.array()).all();
    return out;
  }

  std::unique_ptr<Geometry> uncached;
  std::vector<double> arc;
  const bool by_arc = resampling == Resampling::kArcLength && !periodic && !fit.scaled;
  if (by_arc) {
    const ReparameterMap map(old.degree, old.count(), degree, count, periodic, fit.scaled);
    arc = arc_length_samples(old, map.samples());
    uncached =
        std::make_unique<Geometry>(fit, n_data, degree, count, periodic, target_parameters, &arc);
  }
  const Geometry& G =
      by_arc ? *uncached
             : geometry(fit, n_data, degree, count, periodic, target_parameters, uncached);
  out.parameters = G.params;
  const int w = degree + 1;
  const auto& gb = G.gb;
  const auto& gfirst = G.gfirst;
  const auto& db = G.db;
  const auto& dfirst = G.dfirst;

  // Samples of the old curve (docs/method.md 4 step 1) at tau_l, placed at the new Greville
  // abscissae g_l (step 2).
  std::vector<Point> samples(static_cast<std::size_t>(count));
  const int wo = old.degree + 1, no = old.count();
  for (int l = 0; l < count; ++l) {
    const double* b = &G.sb[static_cast<std::size_t>(l) * wo];
    Point p = Point::Zero();
    for (int i = 0; i < wo; ++i) p += b[i] * old.control[wrap_index(G.sfirst[l] + i, no)];
    samples[l] = p;
  }
  std::vector<double> weight(n_data, 0.0);
  std::vector<std::size_t> order;
  std::optional<detail::BandedLeastSquares> lsq;  // only for repairs
  constexpr int kMaxRounds = 8;
  std::vector<Point> z;
  for (int round = 0;; ++round) {
    if (round == 0) {
      // The paper's re-representation: interpolate the samples (a cached factorisation).
      if (G.singular || !G.interp.replay(samples.data(), out.curve.control, z)) {
        out.holds = false;
        return out;
      }
    } else {
      if (lsq) {
        lsq->reset();
      } else {
        lsq.emplace(count, w, periodic);
      }
      order.clear();
      for (std::size_t k = 0; k < n_data; ++k)
        if (weight[k] > 0) order.push_back(k);
      if (count <= kHeaviestFirstUpTo) {
        // Heaviest equations first (Powell and Reid): the weighted data points, then the
        // samples.
        std::sort(order.begin(), order.end(),
                  [&](std::size_t a, std::size_t b) { return weight[a] > weight[b]; });
        for (std::size_t k : order) lsq->add(dfirst[k], &db[k * w], data[k], weight[k]);
        for (int l = 0; l < count; ++l)
          lsq->add(gfirst[l], &gb[static_cast<std::size_t>(l) * w], samples[l]);
      } else {
        // Long curves: the same equations in the order of their first unknown, the heaviest
        // first among equations on the same one, so that every equation's fill-in stays
        // within the band (see kHeaviestFirstUpTo).
        for (int l = 0; l < count; ++l) order.push_back(n_data + static_cast<std::size_t>(l));
        auto first_of = [&](std::size_t e) { return e < n_data ? dfirst[e] : gfirst[e - n_data]; };
        auto weight_of = [&](std::size_t e) { return e < n_data ? weight[e] : 1.0; };
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
          const int fa = first_of(a), fb = first_of(b);
          if (fa != fb) return fa < fb;
          const double wa = weight_of(a), wb = weight_of(b);
          if (wa != wb) return wa > wb;
          return a < b;
        });
        for (std::size_t e : order) {
          if (e < n_data) {
            lsq->add(dfirst[e], &db[e * w], data[e], weight[e]);
          } else {
            const std::size_t l = e - n_data;
            lsq->add(gfirst[l], &gb[l * w], samples[l]);
          }
        }
      }
      if (!lsq->solve(out.curve.control)) {
        out.holds = false;
        return out;
      }
    }
    // The explicit check of every data point.
    out.max_deviation.setZero();
    bool all = true;
    const auto& P = out.curve.control;
    for (std::size_t k = 0; k < n_data; ++k) {
      Point c = Point::Zero();
      for (int i = 0; i < w; ++i) c += db[k * w + i] * P[wrap_index(dfirst[k] + i, count)];
      const Point d = (c - data[k]).cwiseAbs();
      out.max_deviation = out.max_deviation.cwiseMax(d);
      if (!(d.array() <= bound.array()).all()) {
        all = false;
        weight[k] = weight[k] > 0 ? weight[k] * 1e3 : 1e3;
      }
    }
    out.repair_rounds = round;
    if (all) {
      out.holds = true;
      return out;
    }
    if (round == kMaxRounds) {
      out.holds = false;
      return out;
    }
  }
}

}  // namespace sfit
