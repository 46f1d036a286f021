// Keyword arguments of sfit.fit() and sfit.IncrementalFit() onto FitOptions: one table, one
// line per option (options.cpp), so an option added to FitOptions is one line here.
#pragma once

#include <pybind11/pybind11.h>

#include <optional>
#include <string>

#include "sfit/surface_fit.h"

namespace sfit::python {

namespace py = pybind11;

/// FitOptions plus what needs the rows before it becomes an option (the tolerance).
struct Settings {
  FitOptions options;
  std::optional<Point> tol;       ///< absolute T
  std::optional<double> tol_rel;  ///< fraction of the bounding-box diagonal
};

/// Reads `kwargs` through the table; a value None means "not given" (the library's default).
/// Raises sfit.Error(code "usage", option = the keyword) for an unknown keyword or a bad value.
Settings settings_from(const py::kwargs& kwargs);

/// The options for `rows`: T is tol, or tol_rel (default kDefaultToleranceFraction) of the
/// bounding-box diagonal, as in the CLI.
FitOptions resolve(const Rows& rows, const Settings& settings);

/// "name: what it does" for every keyword, one per line (for the docstrings).
std::string options_doc();

}  // namespace sfit::python
