// The parts of the Python module sfit._sfit, one file each (module.cpp puts them together).
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "sfit/options.h"
#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::python {

namespace py = pybind11;

/// A finished fit as Python sees it: the library's result and the rows it was fitted to
/// (kept for Fit.save()'s deviation fields and Fit.points).
struct PyFit {
  FitResult result;
  std::shared_ptr<const Rows> rows;
};

/// Raises sfit.Error(code "tolerance-not-met") if the fit's report misses the tolerance, as
/// the CLI exits 7 then; the error's `fit` attribute holds the fit.
void check_within_tolerance(const PyFit& fit);

/// Writes `path` through the library's writers (sfit/files.h), as `sfit fit -o`.
/// `output`: save()'s keywords, checked by the library's option table (options.h).
void save_output(const std::string& path, const Surface& surface, const PyFit* fit,
                 const OutputSettings& output);

void bind_errors(py::module_& m);
void bind_surface(py::module_& m);
void bind_fit(py::module_& m);
void bind_curve(py::module_& m);
void bind_io(py::module_& m);
void bind_geometric(py::module_& m);
void bind_options(py::module_& m);  // sfit.fit_options() (options.cpp)
void bind_partial(py::module_& m);  // sfit.dask's chunk pieces (bind_partial.cpp)
void bind_frozen(py::module_& m);   // sfit.FrozenRefit (bind_frozen.cpp)

}  // namespace sfit::python
