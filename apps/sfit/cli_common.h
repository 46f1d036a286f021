// Helpers shared by the sfit subcommands.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <optional>
#include <string>

#include "sfit/files.h"
#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::cli {

/// For every option of `app` and its subcommands that takes a value: an empty value is an
/// error, and a whole number is read in decimal ("010" is 10, "0x10" is refused).
void harden_options(CLI::App& app);

/// The fit's options as the command line gives them; 'fit', 'edit' and 'render-rows' hold them
/// and both check them with check_fit_options(). Flags, help and defaults: the library's option
/// table (sfit/options.h), set by add_fit_option_flags().
/// The table's default of the whole-number option `name` (sfit/options.h).
int table_default_int(std::string_view name);
struct FitOptionArgs {
  int degree = table_default_int("degree");
  std::optional<int> degree_u, degree_v;  // unset: --degree
  std::optional<std::string> tol;
  std::optional<double> tol_rel;
  /// The choice options by table name (closed, search, parameters, method, norm, seam, orient,
  /// rerepresent); "" : not given.
  std::map<std::string, std::string> choices;
  bool no_fold_guard = false;  // docs/seams.md
  int threads = table_default_int("threads");
  /// --closed as given ("" : not given).
  const std::string& closed() const {
    static const std::string none;
    auto it = choices.find("closed");
    return it == choices.end() ? none : it->second;
  }
};
/// Adds the table's fit options (OptionGroup::kFit: --degree ... --threads) to `c`, bound to
/// `a` (fit, edit and render-rows share them).
void add_fit_option_flags(CLI::App* c, FitOptionArgs& a);
/// The table's option `name`: its full help (help, range, default) for a CLI flag.
std::string option_help(std::string_view name);
/// Adds the table's kChoice option `name` (its flag, help and allowed values) bound to `value`.
CLI::Option* add_table_option(CLI::App* c, std::string_view name, std::string& value);
/// Adds the table's kFlag option `name` bound to `value`.
CLI::Option* add_table_flag(CLI::App* c, std::string_view name, bool& value);
/// Checked options: `options` has everything but the tolerance, which comes from the data
/// unless it was given absolutely (tolerance()).
struct CheckedFitOptions {
  FitOptions options;
  Point absolute = Point::Constant(-1);  ///< --tol, or -1: relative
  double fraction = 0;                   ///< --tol-rel or the library's default fraction
  bool relative() const { return absolute.x() < 0; }
  Point tolerance(const Rows& rows) const;
};
/// Every check of the fit's options, through the library's limits (sfit/fit_limits.h);
/// throws Error(kUsage) naming the option.
CheckedFitOptions check_fit_options(const FitOptionArgs& args);

/// The options that shape the surface outputs, as 'fit' and 'convert' take them: flags, help
/// and defaults from the option table, checks by the writers (docs/meshes.md).
struct OutputShapeArgs {
  bool mesh = false;
  int mesh_density = 0;
  bool fields = false;
  bool obj_freeform = false;
  std::string normals = "auto";
  std::string units;  ///< as given; "" : the command's own default
};
/// Adds --mesh, --obj-freeform, --mesh-density, --normals, --fields and --units to `c`.
void add_output_shape_options(CLI::App* c, OutputShapeArgs& a);
/// The writers' context for `surface` with these options and the length unit `units`.
files::OutputContext output_context(const OutputShapeArgs& a, const Surface& surface,
                                    const FitResult* fit, const Rows* rows,
                                    const std::string& input, const std::string& units);

/// Parses "T" or "Tx,Ty,Tz" (each a finite number >= 0); throws Error(kUsage) naming `option`.
Point parse_tolerance(const std::string& text, const std::string& option);

/// Rows of any input format (sfit/files.h).
using Input = files::Input;
/// files::read_input(), saying the length unit of a STEP/IGES input.
Input read_input(const std::string& path);

/// Closed rows the options do not close (a slit in the surface): when every row of a STEP/IGES
/// input is a closed curve and --closed was not given, sets `closed_u` and says so; when every
/// row's ends meet otherwise (or --closed none was given for closed curves), warns.
/// The length unit the STEP/IGES outputs state: --units, else a STEP/IGES input's own unit,
/// else mm; warns when --units differs from the input's unit (coordinates are not converted).
std::string units_of_outputs(const std::string& given, const Input& in);

void note_closed_rows(const Input& in, bool& closed_u, bool closed_given,
                      std::string* note = nullptr);

/// True when messages should be printed (not --quiet).
extern bool verbose;
/// One line to stderr, prefixed "sfit: ".
void say(const std::string& line);

}  // namespace sfit::cli
