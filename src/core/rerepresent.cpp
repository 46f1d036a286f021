#include "sfit/rerepresent.h"

#include <algorithm>
#include <array>
#include <numeric>

#include "banded_lsq.h"
#include "sfit/basis.h"
#include "sfit/parametrization.h"

namespace sfit {

Rerepresentation rerepresent(const CurveFit& fit, std::span<const Point> data, int degree,
                             int count, bool periodic, const Point& bound,
                             std::span<const double> target_parameters) {
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

  const ReparameterMap map(old.degree, old.count(), degree, count, periodic);
  if (target_parameters.empty()) {
    out.parameters.resize(n_data);
    for (std::size_t k = 0; k < n_data; ++k) out.parameters[k] = map(fit.parameters[k]);
  } else {
    out.parameters.assign(target_parameters.begin(), target_parameters.end());
  }

  // Samples of the old curve (METHOD.md 4 step 1) and their places on the new one (step 2).
  const auto& tau = map.samples();
  const auto& g = map.targets();
  const int w = degree + 1;
  std::vector<double> gb(static_cast<std::size_t>(count) * w);
  std::vector<int> gfirst(static_cast<std::size_t>(count));
  std::vector<Point> samples(static_cast<std::size_t>(count));
  for (int l = 0; l < count; ++l) {
    samples[l] = old.evaluate(tau[l]);
    gfirst[l] = eval_basis(degree, count, periodic, g[l], &gb[static_cast<std::size_t>(l) * w]);
  }
  std::vector<double> db(n_data * w);
  std::vector<int> dfirst(n_data);
  for (std::size_t k = 0; k < n_data; ++k)
    dfirst[k] = eval_basis(degree, count, periodic, out.parameters[k], &db[k * w]);

  std::vector<double> weight(n_data, 0.0);
  std::vector<std::size_t> order;
  detail::BandedLeastSquares lsq(count, w, periodic);
  constexpr int kMaxRounds = 8;
  for (int round = 0;; ++round) {
    lsq.reset();
    // Heaviest equations first (Powell and Reid): the weighted data points, then the samples.
    order.clear();
    for (std::size_t k = 0; k < n_data; ++k)
      if (weight[k] > 0) order.push_back(k);
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return weight[a] > weight[b]; });
    for (std::size_t k : order) lsq.add(dfirst[k], &db[k * w], data[k], weight[k]);
    for (int l = 0; l < count; ++l)
      lsq.add(gfirst[l], &gb[static_cast<std::size_t>(l) * w], samples[l]);
    if (!lsq.solve(out.curve.control)) {
      out.holds = false;
      return out;
    }
    // The explicit check of every data point.
    out.max_deviation.setZero();
    bool all = true;
    const auto& P = out.curve.control;
    for (std::size_t k = 0; k < n_data; ++k) {
      Point c = Point::Zero();
      for (int i = 0; i < w; ++i) c += db[k * w + i] * P[(dfirst[k] + i) % count];
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
