// The one table of sfit's fit options: name, type, default, limits, allowed values and help
// of every option of `sfit fit`. The CLI's flags and their help, the Python module's keywords
// (sfit.fit(), Fit.save(), sfit.fit_options()), the editor's limits (GET /api/options-table)
// and docs/options.md are made from it; an option is added here and bound in each front end.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "sfit/fit_limits.h"
#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit {

/// Tessellation samples per direction of a mesh output (0: from the chordal error).
inline constexpr int kMinMeshDensity = 3;
inline constexpr int kMaxMeshDensity = 4096;

enum class OptionType {
  kInteger,    ///< a whole number within [min, max]
  kNumber,     ///< a real number within [min, max]
  kTolerance,  ///< T or (Tx, Ty, Tz), each finite and >= 0
  kChoice,     ///< one of `choices`
  kFlag,       ///< true or false
};
/// What an option shapes: the fit (sfit.fit()'s keywords, the editor's options) or the files
/// written from it (Fit.save()'s / Surface.save()'s keywords, sfit convert's flags).
enum class OptionGroup { kFit, kOutput };

struct OptionSpec {
  std::string_view name;  ///< the Python keyword and the editor's key: "degree_u"
  std::string_view flag;  ///< the CLI's flag: "--degree-u" ("--no-fold-guard" for fold_guard)
  OptionGroup group;
  OptionType type;
  /// The default as text ("3", "auto", "true", "0.001"); "" where it depends on the data or on
  /// another option (help says which).
  std::string default_value;
  double min = 0, max = 0;                ///< kInteger, kNumber: the allowed closed range
  std::vector<std::string_view> choices;  ///< kChoice: every allowed value
  std::string help;                       ///< one line, without the default or the choices
};

/// Every option, in the order of `sfit fit --help`.
const std::vector<OptionSpec>& option_table();
/// The option named `name` (a keyword, e.g. "degree_u"), or nullptr.
const OptionSpec* find_option(std::string_view name);
std::string_view to_string(
    OptionType type);  ///< "integer", "number", "tolerance", "choice", "flag"
std::string_view to_string(OptionGroup group);  ///< "fit", "output"
/// "a, b, c": the allowed values of a kChoice option.
std::string choice_list(const OptionSpec& spec);
/// The option's help with its range and default (flags: none; they are off unless given), as
/// the CLI shows it: "degree in both directions; 1 ... 20 (default 3)".
std::string full_help(const OptionSpec& spec);
/// docs/options.md: the table as Markdown.
std::string option_table_markdown();

/// The fit options as a front end gives them, before the data is known (the tolerance may be
/// a fraction of the data's diagonal).
struct FitSettings {
  FitOptions options;
  std::optional<Point> tol;       ///< absolute T
  std::optional<double> tol_rel;  ///< fraction of the bounding-box diagonal
  /// T for `rows`: tol, else tol_rel (default kDefaultToleranceFraction) of the diagonal.
  Point tolerance(const Rows& rows) const;
};
/// The output options (OptionGroup::kOutput); checked further by the writers themselves.
struct OutputSettings {
  bool mesh = false;
  bool obj_freeform = false;
  int mesh_density = 0;
  std::string normals = "auto";
  bool fields = false;
  std::string units = "mm";
};

/// A value as a front end has it: Python's bool/int/float/str/3 numbers, JSON's, the CLI's.
using OptionValue = std::variant<bool, long long, double, std::string, Point>;

/// Sets the option `name` of the table's kFit group, checked against the table (type, range,
/// allowed values) and the library's rules: throws Error(kUsage, option = `place`) naming the
/// allowed values. An unknown name throws listing the known ones.
void set_fit_option(FitSettings& settings, std::string_view name, const OptionValue& value,
                    const std::string& place);
/// The same for the kOutput group.
void set_output_option(OutputSettings& settings, std::string_view name, const OptionValue& value,
                       const std::string& place);

}  // namespace sfit
