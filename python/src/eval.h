// The parts of sfit.Surface and sfit.Fit that bind_eval.cpp and bind_state.cpp add: evaluation
// (points, derivatives, normals, curvature) from one basis pass per point, closest points,
// Surface.from_knots, pickling of Surface and Fit, and load_surface.
#pragma once

#include <pybind11/pybind11.h>

#include "sfit/surface.h"

namespace sfit::python {

namespace py = pybind11;

/// Adds evaluation, closest points, from_knots and pickling to the Surface class.
void bind_surface_eval(py::class_<Surface>& c);
/// A Surface from its pickled state (the JSON text of __getstate__); raises sfit.Error
/// for anything else.
Surface surface_from_state(py::handle state);
/// sfit.load_surface (JSON, STEP, IGES), Fit pickling; after bind_fit().
void bind_state(py::module_& m);  // bind_state.cpp

}  // namespace sfit::python
