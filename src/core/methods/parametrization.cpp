#include "parameters.h"

#include <algorithm>
#include <cmath>

#include "fit_registry.h"
#include "knots.h"
#include "sfit/error.h"

namespace sfit {
namespace {
double periodic_offset(int degree) {
  return degree % 2 == 0 ? 0.5 : 0.0;
}
double wrap(double t, double period) {
  double r = std::fmod(t, period);
  if (r < 0) r += period;
  if (r >= period) r = 0;
  return r;
}
}  // namespace

std::string_view to_string(Parametrization p) {
  switch (p) {
    case Parametrization::kPaper:
      return "paper";
    case Parametrization::kUniform:
      return "uniform";
    case Parametrization::kChord:
      return "chord";
    case Parametrization::kCentripetal:
      return "centripetal";
    case Parametrization::kGeometric:
      return "geometric";
    case Parametrization::kFewest:
      return "fewest";
    case Parametrization::kAuto:
      return "auto";
  }
  return detail::rule_name(p);  // a registered rule ("" where none is)
}

bool parse_parametrization(std::string_view name, Parametrization& out) {
  if (const detail::RuleEntry* e = detail::rule_entry(name)) {
    out = e->id;
    return true;
  }
  return false;
}

namespace {
// A registered rule's positions (fit_registry.h), checked: one per point, in [0, 1],
// nondecreasing, the first 0 and (open rows) the last 1.
std::vector<double> registered_positions(std::span<const Point> points, Parametrization rule,
                                         bool periodic) {
  const detail::RuleEntry* e = detail::rule_entry(rule);
  if (!e || !e->positions)
    throw Error(ErrorCode::kUsage,
                "parameters: no row rule registered as " + std::to_string(static_cast<int>(rule)),
                Place{.option = "parameters"}, {static_cast<double>(rule)});
  std::vector<double> f = e->positions(points, periodic);
  bool ok = f.size() == points.size();
  for (std::size_t j = 0; ok && j < f.size(); ++j)
    ok = std::isfinite(f[j]) && f[j] >= 0 && f[j] <= 1 && (j == 0 || f[j] >= f[j - 1]);
  if (ok && !f.empty()) ok = f.front() == 0 && (periodic || f.size() < 2 || f.back() == 1);
  if (!ok)
    throw Error(ErrorCode::kUsage,
                "parameters " + e->name + " gave " + std::to_string(f.size()) +
                    " positions for a row of " + std::to_string(points.size()) +
                    " points, not nondecreasing from 0 to 1",
                Place{.option = "parameters"});
  return f;
}
}  // namespace

std::vector<double> normalized_positions(std::span<const Point> points, Parametrization rule,
                                         bool periodic) {
  if (static_cast<int>(rule) > static_cast<int>(Parametrization::kAuto))
    return registered_positions(points, rule, periodic);
  const std::size_t n = points.size();
  std::vector<double> f(n, 0.0);
  if (n < 2) return f;
  const std::size_t steps = periodic ? n : n - 1;
  double total = 0;
  if (rule == Parametrization::kChord || rule == Parametrization::kCentripetal) {
    for (std::size_t j = 1; j <= steps; ++j) {
      const double d = (points[j % n] - points[j - 1]).norm();
      total += rule == Parametrization::kCentripetal ? std::sqrt(d) : d;
      if (j < n) f[j] = total;
    }
  }
  if (!(total > 0) || !std::isfinite(total)) {  // kUniform, or all points coincide
    for (std::size_t j = 0; j < n; ++j) f[j] = static_cast<double>(j) / steps;
  } else {
    for (std::size_t j = 1; j < n; ++j) f[j] /= total;
  }
  if (!periodic) f[n - 1] = 1.0;  // exact end despite round-off
  return f;
}

std::vector<double> scaled_parameters(int degree, int count, bool periodic,
                                      std::span<const double> positions) {
  std::vector<double> t(positions.size());
  if (periodic) {
    const double o = periodic_offset(degree);
    for (std::size_t j = 0; j < t.size(); ++j) t[j] = wrap(o + positions[j] * count, count);
    return t;
  }
  const double length = domain_end(degree, count, false);
  for (std::size_t j = 0; j < t.size(); ++j) t[j] = positions[j] * length;
  if (!t.empty() && positions.back() == 1.0) t.back() = length;
  return t;
}

std::vector<double> paper_parameters(int degree, int count, bool periodic, int n_points) {
  std::vector<double> t(static_cast<std::size_t>(n_points));
  if (periodic) {
    const double o = periodic_offset(degree);
    for (int j = 0; j < n_points; ++j)
      t[j] = wrap(o + static_cast<double>(j) * count / n_points, count);
    return t;
  }
  if (n_points == 1 || count == 1) {
    std::fill(t.begin(), t.end(), 0.0);
    if (n_points > 1) t.back() = domain_end(degree, count, false);
    return t;
  }
  // The Greville sequence once, then read at fractional indices (greville_at() per point
  // would recompute two abscissae each time).
  std::vector<double> g(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) g[i] = greville(degree, count, false, i);
  const double a = static_cast<double>(count - 1) / (n_points - 1);
  for (int j = 0; j < n_points; ++j) {
    const double x = a * j;
    int m = static_cast<int>(x);
    if (m >= count - 1) m = count - 2;
    t[j] = g[m] + (x - m) * (g[m + 1] - g[m]);
  }
  t[n_points - 1] = domain_end(degree, count, false);  // exact end despite round-off
  return t;
}

ReparameterMap::ReparameterMap(int degree_from, int count_from, int degree_to, int count_to,
                               bool periodic, bool scaled)
    : periodic_(periodic), scaled_(scaled && !periodic) {
  tau_.resize(static_cast<std::size_t>(count_to));
  g_.resize(static_cast<std::size_t>(count_to));
  if (periodic) {
    scale_ = static_cast<double>(count_to) / count_from;
    offset_from_ = periodic_offset(degree_from);
    offset_to_ = periodic_offset(degree_to);
    period_to_ = count_to;
    for (int l = 0; l < count_to; ++l) {
      tau_[l] = wrap(offset_from_ + l / scale_, count_from);
      g_[l] = wrap(offset_to_ + l, count_to);
    }
    return;
  }
  if (scaled_) {
    // Domain onto domain: [0, count_from - degree_from] to [0, count_to - degree_to].
    scale_ = domain_end(degree_to, count_to, false) / domain_end(degree_from, count_from, false);
    for (int l = 0; l < count_to; ++l) {
      g_[l] = greville(degree_to, count_to, false, l);
      tau_[l] = std::min(g_[l] / scale_, domain_end(degree_from, count_from, false));
    }
    return;
  }
  const double a = count_to > 1 ? static_cast<double>(count_from - 1) / (count_to - 1) : 0.0;
  for (int l = 0; l < count_to; ++l) {
    tau_[l] = greville_at(degree_from, count_from, false, a * l);
    g_[l] = greville(degree_to, count_to, false, l);
  }
}

double ReparameterMap::operator()(double t) const {
  if (periodic_) return wrap(offset_to_ + (t - offset_from_) * scale_, period_to_);
  if (scaled_) return std::clamp(t * scale_, g_.front(), g_.back());
  const std::size_t n = tau_.size();
  if (n == 1) return g_[0];
  if (t <= tau_.front()) return g_.front();
  if (t >= tau_.back()) return g_.back();
  const std::size_t l =
      static_cast<std::size_t>(std::upper_bound(tau_.begin(), tau_.end(), t) - tau_.begin()) - 1;
  const double d = tau_[l + 1] - tau_[l];
  const double f = d > 0 ? (t - tau_[l]) / d : 0.0;
  return g_[l] + f * (g_[l + 1] - g_[l]);
}

}  // namespace sfit
