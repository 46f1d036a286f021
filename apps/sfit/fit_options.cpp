#include "fit_options.h"

#include <fmt/format.h>

#include "cli_common.h"
#include "sfit/error.h"

namespace sfit::cli {

void add_fit_option_flags(CLI::App* c, FitOptionArgs& a) {
  c->add_option("--degree", a.degree, "degree in both directions, 1 ... 20")->default_val(3);
  c->add_option("--degree-u", a.degree_u, "degree along the rows (overrides --degree)");
  c->add_option("--degree-v", a.degree_v, "degree across the rows (overrides --degree)");
  c->add_option("--tol", a.tol,
                "tolerance T or Tx,Ty,Tz, absolute, >= 0 (0 interpolates); "
                "default 1e-3 of the bounding-box diagonal");
  c->add_option("--tol-rel", a.tol_rel, "tolerance as a fraction of the bounding-box diagonal");
  c->add_option("--closed", a.closed,
                "closed directions: u (each row is a closed contour), v (the rows form a "
                "closed sequence), uv (both), none");
  c->add_option("--search", a.search, "count search: fast (default) or linear (the paper's)")
      ->check(CLI::IsMember({"fast", "linear"}));
  c->add_option("--parameters", a.parameters,
                "how points get parameters, along and across the rows: paper (SFIT01's, by the "
                "point's index; default), uniform (index), chord (chord length), centripetal, or "
                "fewest (tries the four, keeps the fewest control points)")
      ->check(CLI::IsMember({"paper", "uniform", "chord", "centripetal", "fewest"}));
  c->add_option("--threads", a.threads, "threads (0: all cores); results do not depend on it")
      ->check(CLI::Range(0, 4096));
}

FitOptionPlan plan_fit_options(const FitOptionArgs& a) {
  FitOptionPlan plan;
  FitOptions& o = plan.options;
  o.degree_u = a.degree_u.value_or(a.degree);
  o.degree_v = a.degree_v.value_or(a.degree);
  auto check_degree = [](int d, const char* opt) {
    if (d < 1 || d > 20)
      throw Error(ErrorCode::kUsage, fmt::format("degree {} is out of range 1 ... 20", d),
                  Place{.option = opt}, {static_cast<double>(d)});
  };
  check_degree(a.degree, "--degree");
  if (a.degree_u) check_degree(*a.degree_u, "--degree-u");
  if (a.degree_v) check_degree(*a.degree_v, "--degree-v");
  if (a.closed == "u" || a.closed == "uv" || a.closed == "vu") o.closed_u = true;
  if (a.closed == "v" || a.closed == "uv" || a.closed == "vu") o.closed_v = true;
  if (!a.closed.empty() && a.closed != "none" && !o.closed_u && !o.closed_v)
    throw Error(ErrorCode::kUsage, "'" + a.closed + "' is not one of u, v, uv, none",
                Place{.option = "--closed"});
  o.search = a.search == "linear" ? CountSearch::kLinear : CountSearch::kFast;
  parse_parametrization(a.parameters, o.parametrization);  // checked by CLI11
  o.threads = a.threads;
  if (a.tol && a.tol_rel)
    throw Error(ErrorCode::kUsage, "give --tol or --tol-rel, not both",
                Place{.option = "--tol-rel"});
  if (a.tol_rel && !(*a.tol_rel >= 0 && *a.tol_rel <= 1))
    throw Error(
        ErrorCode::kUsage,
        fmt::format("must be a fraction 0 ... 1 of the bounding-box diagonal, got {}", *a.tol_rel),
        Place{.option = "--tol-rel"}, {*a.tol_rel});
  if (a.tol) plan.absolute_tolerance = parse_tolerance(*a.tol, "--tol");
  plan.fraction = a.tol_rel.value_or(1e-3);
  return plan;
}

Point tolerance_for(const FitOptionPlan& plan, const Rows& rows) {
  if (plan.absolute_tolerance) return *plan.absolute_tolerance;
  return Point::Constant(plan.fraction * bounding_box(rows).diagonal());
}

}  // namespace sfit::cli
