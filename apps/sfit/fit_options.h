// The fit options of `sfit fit`, shared by every command that fits (fit, edit): one place
// registers them and turns them into FitOptions, so no command restates their rules.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::cli {

/// The fit options as given on the command line.
struct FitOptionArgs {
  int degree = 3;
  std::optional<int> degree_u, degree_v;  // unset: --degree
  std::optional<std::string> tol;
  std::optional<double> tol_rel;
  std::string closed;
  std::string search = "fast";
  std::string parameters = "paper";
  int threads = 0;
};

/// Adds --degree, --degree-u, --degree-v, --tol, --tol-rel, --closed, --search, --parameters
/// and --threads to `c`, bound to `a`.
void add_fit_option_flags(CLI::App* c, FitOptionArgs& a);

/// FitOptions from the arguments, checked (Error(kUsage) naming the option); the tolerance is
/// left for tolerance_for(), which needs the data.
struct FitOptionPlan {
  FitOptions options;
  std::optional<Point> absolute_tolerance;  ///< --tol
  double fraction = 1e-3;                   ///< --tol-rel, or its default
};
FitOptionPlan plan_fit_options(const FitOptionArgs& a);

/// The absolute tolerance the plan means for `rows`.
Point tolerance_for(const FitOptionPlan& plan, const Rows& rows);

}  // namespace sfit::cli
