// The parts of sfit.Surface and sfit.Fit that bind_eval.cpp adds: evaluation (points,
// derivatives, normals, curvature) from one basis pass per point, closest points,
// Surface.from_knots, pickling of Surface and Fit, and load_surface.
#pragma once

#include <pybind11/pybind11.h>

#include "sfit/surface.h"

namespace sfit::python {

namespace py = pybind11;

/// Adds evaluation, closest points, from_knots and pickling to the Surface class.
void bind_surface_eval(py::class_<Surface>& c);
/// sfit.load_surface (JSON, STEP, IGES), Fit pickling; after bind_fit().
void bind_eval_module(py::module_& m);

}  // namespace sfit::python
