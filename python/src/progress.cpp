#include "progress.h"

#include <memory>
#include <optional>
#include <string>

#include "sfit/error.h"

namespace sfit::python {
namespace {

// A copy of sfit::FitProgress that owns its phase name.
struct PyProgress {
  std::string phase;
  std::size_t done = 0, total = 0;
  long pairs_tried = 0;
  int best_u = 0, best_v = 0;
  double seconds = 0;
};

// What stopped a fit on the Python side: a signal's exception (KeyboardInterrupt) or the
// progress callable's own.
struct Stop {
  std::optional<py::error_already_set> error;
};

}  // namespace

void bind_progress(py::module_& m) {
  py::class_<PyProgress>(m, "FitProgress",
                         "What a fit is doing, passed to the `progress` callable of sfit.fit().")
      .def_readonly("phase", &PyProgress::phase,
                    "'search' (the surface search's pairs), 'lower bound', 'rows' (curve "
                    "stage), 'columns' (transverse stage), 'check', 'fold guard'")
      .def_readonly("done", &PyProgress::done, "items of the phase done")
      .def_readonly("total", &PyProgress::total, "items in the phase")
      .def_readonly("pairs_tried", &PyProgress::pairs_tried,
                    "(nu, nv) pairs the surface search solved at so far")
      .def_property_readonly(
          "best",
          [](const PyProgress& p) -> py::object {
            if (p.best_u == 0) return py::none();
            return py::make_tuple(p.best_u, p.best_v);
          },
          "(nu, nv): the fewest control points found to hold so far, or None")
      .def_readonly("seconds", &PyProgress::seconds, "seconds since the fit started")
      .def("__repr__", [](const PyProgress& p) {
        return "<sfit.FitProgress " + p.phase + " " + std::to_string(p.done) + "/" +
               std::to_string(p.total) + ", " + std::to_string(p.pairs_tried) + " pairs tried, " +
               (p.best_u > 0 ? std::to_string(p.best_u) + " x " + std::to_string(p.best_v)
                             : std::string("no best yet")) +
               ", " + std::to_string(p.seconds) + " s>";
      });
}

ProgressFunction python_progress(py::handle callable) {
  // Shared, never copied as a Python object while the GIL is released; released with the
  // GIL held.
  std::shared_ptr<py::object> f(new py::object(py::reinterpret_borrow<py::object>(callable)),
                                [](py::object* o) {
                                  py::gil_scoped_acquire gil;
                                  delete o;
                                });
  return [f](const FitProgress& p) {
    py::gil_scoped_acquire gil;
    PyProgress copy{
        std::string(p.phase), p.done, p.total, p.pairs_tried, p.best_u, p.best_v, p.seconds};
    const py::object r = (*f)(std::move(copy));  // a Python exception: error_already_set
    return !(r.ptr() == Py_False);
  };
}

void run_fit(FitOptions& options, const std::function<void()>& work) {
  auto stop = std::make_shared<Stop>();
  // Python runs signal handlers on its main thread only: elsewhere, no check to make.
  const py::module_ threading = py::module_::import("threading");
  const bool main_thread = threading.attr("current_thread")().is(threading.attr("main_thread")());
  if (!main_thread && !options.progress) {
    py::gil_scoped_release nogil;
    work();
    return;
  }
  options.progress = [stop, main_thread, user = std::move(options.progress)](const FitProgress& p) {
    try {
      if (user && !user(p)) return false;
      if (main_thread) {
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      }
    } catch (py::error_already_set& e) {
      stop->error = std::move(e);
      return false;
    }
    return true;
  };
  try {
    py::gil_scoped_release nogil;
    work();
  } catch (const Error& e) {
    options.progress = {};
    if (e.code() == ErrorCode::kCancelled && stop->error) throw *stop->error;
    throw;
  }
  options.progress = {};
}

}  // namespace sfit::python
