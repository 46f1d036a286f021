// Plug-in fit methods and parameter rules (docs/method.md 7.11, "How a fit runs"): an
// application registers its own under a name, with a help line and a function, and selects it
// like a built-in (FitOptions::method / ::parametrization = the handle's id, or by name through
// the option table: `set_fit_option(settings, "method", "my_method", ...)`). The option table,
// and so a CLI's --help, Python's fit_options() and the editor, lists it while registered.
// Register before fitting, not while a fit runs.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "sfit/parametrization.h"
#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit {

/// What the fit driver hands a registered method: the rows validated (sfit::validate()),
/// their seams and orientation aligned, and centred once. The method returns its candidate
/// surface in the data's coordinates (the centre added back), with u, v of these rows' points
/// and its report; report.within_tolerance is its own claim: the driver's final check of the
/// surface as returned, at every point, decides. A method never validates or checks.
struct MethodInput {
  const Rows& rows;                      ///< validated, aligned, in the data's coordinates
  const FitOptions& options;             ///< seam and orient kKeep (the rows are aligned)
  std::span<const double> seam_offsets;  ///< fractional seams of the aligned rows; empty: none
  const Rows& centred;                   ///< `rows` less `centre`
  Point centre = Point::Zero();          ///< the centre of `box`
  BoundingBox box;                       ///< of `rows`
  double roundoff = 0;                   ///< the checks' round-off allowance (of the diagonal)
  int threads = 1;                       ///< the threads the fit may use
};

/// A fit method: the driver's input to a candidate surface with its report.
using FitMethodFunction = std::function<FitResult(const MethodInput&)>;

/// A row rule: the positions f_0 ... f_{N-1} of a row's points as fractions of the row, one
/// per point, nondecreasing from 0, ending at 1 on open rows and below 1 on closed ones
/// (`periodic`); used along the rows, and across them averaged over the columns as for the
/// chord rule. Positions that break this are a usage error (ErrorCode::kUsage) of the fit.
using RowRuleFunction =
    std::function<std::vector<double>(std::span<const Point> points, bool periodic)>;

/// A method registered while the handle lives. Throws Error(kUsage) where `name` is empty or
/// taken (a built-in's or another registered one's). Move-only.
class RegisteredMethod {
 public:
  RegisteredMethod(std::string name, std::string help, FitMethodFunction fit);
  ~RegisteredMethod();
  RegisteredMethod(RegisteredMethod&& other) noexcept;
  RegisteredMethod& operator=(RegisteredMethod&& other) noexcept;
  RegisteredMethod(const RegisteredMethod&) = delete;
  RegisteredMethod& operator=(const RegisteredMethod&) = delete;
  /// The value of FitOptions::method that selects it (and FitReport::method names).
  FitMethod id() const { return id_; }

 private:
  FitMethod id_{};
  bool owns_ = false;
};

/// Whether the automatic choices (Parametrization::kAuto and kFewest) try a registered rule
/// beside the built-ins, keeping it where its surface has the fewest control points, or only
/// a fit that names it uses it.
enum class RuleUse {
  kWhenNamed,  ///< only FitOptions::parametrization = its id (or its name) selects it
  /// also tried, after the built-ins, by `auto` and `fewest` of the surface method and by
  /// `fewest` of the two stages (whose `auto` is the paper's rule)
  kAlsoAuto,
};

/// A parameter rule registered while the handle lives; as RegisteredMethod.
class RegisteredRule {
 public:
  RegisteredRule(std::string name, std::string help, RowRuleFunction positions,
                 RuleUse use = RuleUse::kWhenNamed);
  ~RegisteredRule();
  RegisteredRule(RegisteredRule&& other) noexcept;
  RegisteredRule& operator=(RegisteredRule&& other) noexcept;
  RegisteredRule(const RegisteredRule&) = delete;
  RegisteredRule& operator=(const RegisteredRule&) = delete;
  /// The value of FitOptions::parametrization that selects it.
  Parametrization id() const { return id_; }

 private:
  Parametrization id_{};
  bool owns_ = false;
};

}  // namespace sfit
