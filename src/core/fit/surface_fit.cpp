// fit_surface(): the driver (fit_driver.h) under progress and cancel, and the names of
// methods (the registry's, fit_registry.h), norms and knot rules.
#include "sfit/surface_fit.h"

#include <optional>

#include "fit_driver.h"
#include "fit_monitor.h"
#include "fit_registry.h"
#include "parse_name.h"

namespace sfit {

std::string_view to_string(FitMethod m) {
  if (m == FitMethod::kSfit01) return "sfit01";
  if (m == FitMethod::kSurface) return "surface";
  return detail::method_name(m);  // a registered method ("" where none is)
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
  for (const detail::MethodEntry& e : detail::methods())
    if (e.name == name) {
      out = e.id;
      return true;
    }
  return false;
}

std::string_view to_string(KnotRule k) {
  return k == KnotRule::kAdaptive ? "adaptive" : k == KnotRule::kCorners ? "corners" : "uniform";
}

bool parse_knot_rule(std::string_view name, KnotRule& out) {
  return detail::parse_name(name, {KnotRule::kUniform, KnotRule::kAdaptive, KnotRule::kCorners},
                            out);
}

bool parse_fit_norm(std::string_view name, FitNorm& out) {
  return detail::parse_name(name, {FitNorm::kL2, FitNorm::kLinf, FitNorm::kAuto}, out);
}

FitResult fit_surface(const Rows& rows, const FitOptions& o) {
  // Progress and cancel (sfit/progress.h) for the whole fit, on every thread it uses.
  std::optional<detail::FitMonitor> monitor;
  if (detail::FitMonitor::wanted(o) && !detail::current_monitor()) monitor.emplace(o);
  const detail::MonitorScope scope(monitor ? &*monitor : detail::current_monitor());
  return detail::run_fit(rows, o);
}

}  // namespace sfit
