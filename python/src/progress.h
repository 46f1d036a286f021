// Progress and Ctrl-C of a fit run from Python (progress.cpp): the `progress` keyword's
// callable, and the check for signals (KeyboardInterrupt) while the fit runs without the GIL.
#pragma once

#include <pybind11/pybind11.h>

#include <functional>

#include "sfit/surface_fit.h"

namespace sfit::python {

namespace py = pybind11;

/// sfit.FitProgress, the one argument of the `progress` callable.
void bind_progress(py::module_& m);

/// FitOptions::progress for the `progress` keyword: calls `callable(sfit.FitProgress)` with
/// the GIL; a return of False stops the fit. A Python exception it raises stops the fit too
/// and reaches the caller of run_fit().
ProgressFunction python_progress(py::handle callable);

/// Runs `work` (a fit with `options`) with the GIL released. While it runs, the fit's thread
/// takes the GIL every kProgressInterval seconds (with the `progress` callable, if any) and
/// checks for signals: Ctrl-C raises KeyboardInterrupt here within a fraction of a second.
/// A progress callable that raised: its exception, raised here. One that returned False:
/// sfit.Error with code "cancelled".
void run_fit(FitOptions& options, const std::function<void()>& work);

}  // namespace sfit::python
