// Keyword arguments of sfit.fit() and sfit.IncrementalFit() onto FitOptions, and of save():
// the library's option table (sfit/options.h) makes them; options.cpp only converts Python
// values by the table's types (plus the module's own count hints and progress callback).
#pragma once

#include <pybind11/pybind11.h>

#include <optional>
#include <string>

#include "sfit/options.h"
#include "sfit/surface_fit.h"

namespace sfit::python {

namespace py = pybind11;

/// FitOptions plus what needs the rows before it becomes an option (the tolerance).
using Settings = FitSettings;

/// Reads `kwargs` through the table; a value None means "not given" (the library's default).
/// Raises sfit.Error(code "usage", option = the keyword) for an unknown keyword or a bad value.
Settings settings_from(const py::kwargs& kwargs);

/// The options for `rows`: T is tol, or tol_rel (default kDefaultToleranceFraction) of the
/// bounding-box diagonal, as in the CLI.
FitOptions resolve(const Rows& rows, const Settings& settings);

/// "name: what it does" for every keyword, one per line (for the docstrings).
std::string options_doc();

/// sfit.fit_options(): the table as a list of dicts (name, flag, group, type, default, min,
/// max, choices, help).
py::list fit_options();

/// save()'s keywords checked by the table (Error(kUsage) naming the keyword).
OutputSettings output_settings(bool mesh, int mesh_density, bool fields, const std::string& units,
                               bool obj_freeform, const std::string& normals);
/// The table's default of an output option as a Python value (for save()'s signature).
py::object output_default(const char* name);

/// sfit.fit_options().
void bind_options(py::module_& m);

}  // namespace sfit::python
