// fit_surface(): the method's dispatch, and the names of methods and norms.
#include "sfit/surface_fit.h"

#include <optional>

#include "adaptive_knots.h"
#include "fit_monitor.h"
#include "parse_name.h"
#include "surface_fitter.h"

namespace sfit {

std::string_view to_string(FitMethod m) {
  return m == FitMethod::kSfit01 ? "sfit01" : "surface";
}

std::string_view to_string(FitNorm n) {
  switch (n) {
    case FitNorm::kL2:
      return "l2";
    case FitNorm::kLinf:
      return "linf";
    case FitNorm::kAuto:
      return "auto";
  }
  return "auto";
}

bool parse_fit_method(std::string_view name, FitMethod& out) {
  return detail::parse_name(name, {FitMethod::kSurface, FitMethod::kSfit01}, out);
}

std::string_view to_string(KnotRule k) {
  return k == KnotRule::kAdaptive ? "adaptive" : "uniform";
}

bool parse_knot_rule(std::string_view name, KnotRule& out) {
  return detail::parse_name(name, {KnotRule::kUniform, KnotRule::kAdaptive}, out);
}

bool parse_fit_norm(std::string_view name, FitNorm& out) {
  return detail::parse_name(name, {FitNorm::kL2, FitNorm::kLinf, FitNorm::kAuto}, out);
}

FitResult fit_surface(const Rows& rows, const FitOptions& o) {
  // Progress and cancel (sfit/progress.h) for the whole fit, on every thread it uses.
  std::optional<detail::FitMonitor> monitor;
  if (detail::FitMonitor::wanted(o) && !detail::current_monitor()) monitor.emplace(o);
  const detail::MonitorScope scope(monitor ? &*monitor : detail::current_monitor());
  detail::SurfaceFitter fitter(o);
  FitResult r = fitter.fit(rows);
  if (o.knots == KnotRule::kAdaptive) detail::adapt_knots(rows, o, r);
  return r;
}

}  // namespace sfit
