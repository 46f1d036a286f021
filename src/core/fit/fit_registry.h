// The registries of fit methods and parameter rules (docs/method.md, "How a fit runs"):
// every method and rule is a plug-in with a name, a help line and a function. The built-ins
// register in fit_registry.cpp, one line each; a test or an application registers more through
// the public face, sfit/fit_registry.h (RegisteredMethod, RegisteredRule).
// FitOptions names one by its id: a FitMethod / Parametrization value, the built-ins' enum
// values or the id register_*() handed out. The option table's allowed values of `method` and
// `parameters` (and so the CLI's --help, Python, the editor and docs/options.md) list the
// registries. Register before fitting, not while a fit runs. Private.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fit_driver.h"
#include "sfit/parametrization.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

/// A method: validated, centred, aligned rows (FitSpec) to a candidate surface with its
/// report (within_tolerance is the method's own verdict; the driver's final check decides).
using MethodFunction = std::function<FitResult(const FitSpec&)>;

/// A method's state between the fits of IncrementalFit (docs/method.md 7.7), for a method that
/// can refit only what an edit of some rows touches. The driver runs it (run_fit(), fit_driver.h)
/// as it runs MethodEntry::fit: on validated, aligned, centred rows, with the final check after.
class MethodState {
 public:
  virtual ~MethodState() = default;
  /// The method on `spec`, as MethodEntry::fit does it, keeping what update() may reuse.
  virtual FitResult fit(const FitSpec& spec) = 0;
  /// Exactly fit(spec) (bit for bit) after the rows in `changed` were edited (spec.rows: the
  /// edited rows, as many as before and in their order), refitting only what the edits touch.
  virtual FitResult update(const FitSpec& spec, const std::vector<std::size_t>& changed) = 0;
  /// The next update() refits in full.
  virtual void forget() = 0;
  /// Rows whose curves the last fit() or update() refitted.
  virtual std::size_t rows_refitted() const = 0;
};
/// A method's state for the options given (the driver's: seam and orient kKeep).
using StateFunction = std::function<std::unique_ptr<MethodState>(const FitOptions&)>;

struct MethodEntry {
  FitMethod id{};
  std::string name;  ///< the option value: "surface"
  std::string help;  ///< one line for the option table, without the name
  MethodFunction fit;
  /// IncrementalFit's state where the method has one; empty: every edit refits in full.
  StateFunction incremental;
};

/// Positions f_0 ... f_{N-1} of a row's points as fractions of the row (as
/// normalized_positions(): open rows 0 ... 1, closed rows 0 up to below 1, nondecreasing).
using PositionFunction = std::function<std::vector<double>(std::span<const Point>, bool periodic)>;

struct RuleEntry {
  Parametrization id{};
  std::string name;  ///< the option value: "chord"
  std::string help;  ///< one line for the option table, without the name; may be empty
  /// The row rules' positions (along a row; across the rows averaged over the columns as for
  /// the chord rule); empty for the paper's rule (Greville), the geometric rule (per point) and
  /// the choices that are no rule (fewest, auto).
  PositionFunction positions;
  /// Tried by the automatic choices (kAuto, kFewest) beside the built-ins (registered rules
  /// that opted in; the built-ins are listed by rules_of() and SurfaceFitter themselves).
  bool automatic = false;
};

/// The method registered as `id`; throws Error(kUsage, option "method") where none is.
MethodEntry method_entry(FitMethod id);
/// The method named `name`; throws Error(kUsage, option "method") naming the registered ones.
MethodEntry method_entry(std::string_view name);
/// The rule registered as `id`, or nullptr (entries are never freed: the pointer stays valid).
const RuleEntry* rule_entry(Parametrization id);
const RuleEntry* rule_entry(std::string_view name);
/// The name of the method / rule registered as `id` ("" where none is), stable storage.
std::string_view method_name(FitMethod id);
std::string_view rule_name(Parametrization id);
/// Every registered method / rule, built-ins first, in registration order.
std::vector<MethodEntry> methods();
std::vector<RuleEntry> rules();
/// The registered (not built-in) rules the automatic choices try, in registration order.
std::vector<Parametrization> automatic_rules();
/// Changes with every registration or removal (the option table rebuilds on it).
long registry_generation();

/// Registers a method or rule under a new name; its id. Throws Error(kUsage) on a name taken.
FitMethod register_method(std::string name, std::string help, MethodFunction fit);
Parametrization register_rule(std::string name, std::string help, PositionFunction positions,
                              bool automatic = false);
/// Removes a registered method or rule (not a built-in); its name is free again.
void unregister_method(FitMethod id);
void unregister_rule(Parametrization id);

}  // namespace sfit::detail
