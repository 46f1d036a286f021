// sfit._sfit: the compiled part of the Python package sfit (python/sfit/__init__.py).
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "eval.h"
#include "progress.h"
#include "sfit/version.h"

PYBIND11_MODULE(_sfit, m) {
  m.doc() =
      "sfit: rows of 3D points to one B-spline surface within a per-axis tolerance, with as "
      "few control points as possible (docs/python.md).";
  m.attr("__version__") = sfit::kVersion;
  sfit::python::bind_errors(m);
  sfit::python::bind_surface(m);
  sfit::python::bind_curve(m);
  sfit::python::bind_progress(m);
  sfit::python::bind_fit(m);
  sfit::python::bind_frozen(m);
  sfit::python::bind_io(m);
  sfit::python::bind_state(m);
  sfit::python::bind_options(m);
  sfit::python::bind_partial(m);
  sfit::python::bind_geometric(m);
}
