// Helpers shared by the sfit subcommands.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::cli {

/// For every option of `app` and its subcommands that takes a value: an empty value is an
/// error, and a whole number is read in decimal ("010" is 10, "0x10" is refused).
void harden_options(CLI::App& app);

/// The fit's options as the command line gives them; 'fit', 'edit' and 'render-rows' hold them
/// and both check them with check_fit_options().
struct FitOptionArgs {
  int degree = 3;
  std::optional<int> degree_u, degree_v;  // unset: --degree
  std::optional<std::string> tol;
  std::optional<double> tol_rel;
  std::string closed;
  std::string search = "fast";
  std::string parameters = "auto";
  std::string method = "surface", norm = "auto";
  std::string seam = "align", orient = "auto", rerepresent = "paper";  // docs/seams.md
  bool no_fold_guard = false;                                          // docs/seams.md
  int threads = 0;
};
/// Adds --degree, --degree-u, --degree-v, --tol, --tol-rel, --closed, --search, --parameters,
/// --method, --norm, --seam, --orient, --no-fold-guard, --rerepresent and --threads to `c`, bound
/// to `a` (fit and edit share them).
void add_fit_option_flags(CLI::App* c, FitOptionArgs& a);
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

/// Parses "T" or "Tx,Ty,Tz" (each a finite number >= 0); throws Error(kUsage) naming `option`.
Point parse_tolerance(const std::string& text, const std::string& option);

/// Reads input rows by extension (.rows, and whatever the exchange part adds: .csv, .step,
/// .iges); "-" reads .rows from standard input.
struct Input {
  Rows rows;
  std::vector<long> first_line;  ///< line of each row's first point, where the format has lines
  std::string name;
  std::vector<bool> closed_rows;  ///< STEP/IGES: the row is a closed curve (empty otherwise)
  std::string units;              ///< STEP/IGES: the file's length unit (mm, m, in, ...)
};
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
