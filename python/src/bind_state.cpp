// The states behind pickling and copying of sfit.Surface and sfit.Fit (read back by
// sfit._state), and sfit.load_surface.
#include <pybind11/stl.h>

#include <cstring>
#include <memory>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "errors.h"
#include "eval.h"
#include "sfit/exchange/surface_reader.h"
#include "sfit/io/file_names.h"
#include "sfit/io/report_json.h"
#include "sfit/io/surface_json.h"

namespace sfit::python {

Surface surface_from_state(py::handle state) {
  if (!py::isinstance<py::str>(state))
    throw Error(ErrorCode::kInputData,
                "a Surface state is the JSON text Surface.__getstate__() returns, got " +
                    std::string(py::str(py::type::of(state).attr("__name__"))),
                Place{.file = "pickle"});
  return io::surface_from_json_text(py::cast<std::string>(state), "pickle");
}

namespace {

// A Fit as plain values: the surface and report as sfit's JSON (doubles round-trip exactly),
// the parameters, points and weights as bytes. Version 2 adds the points' own v
// (Fit.v_points, parameters 'geometric'); version 1 states (8 values) are still read.
py::tuple fit_state(const PyFit& f) {
  const Rows& r = *f.rows;
  std::vector<long> sizes;
  for (std::size_t j = 0; j < r.size(); ++j) sizes.push_back(static_cast<long>(r[j].size()));
  auto bytes = [](const void* p, std::size_t n) {
    return py::bytes(static_cast<const char*>(p), n);
  };
  return py::make_tuple(2, io::surface_to_json_text(f.result.surface),
                        io::report_to_json_text(f.result.report, -1),
                        bytes(f.result.u.data(), f.result.u.size() * sizeof(double)),
                        bytes(f.result.v.data(), f.result.v.size() * sizeof(double)),
                        bytes(r.points().data(), r.total_points() * sizeof(Point)), sizes,
                        bytes(r.weights().data(), r.weights().size() * sizeof(double)),
                        bytes(f.result.v_points.data(), f.result.v_points.size() * sizeof(double)));
}

template <class T>
std::vector<T> from_bytes(py::handle b, const char* what) {
  const std::string s = py::cast<std::string>(b);
  if (s.size() % sizeof(T) != 0) data_error(std::string("Fit state: ") + what + " is cut short");
  std::vector<T> out(s.size() / sizeof(T));
  if (!out.empty()) std::memcpy(static_cast<void*>(out.data()), s.data(), s.size());
  return out;
}

PyFit fit_from_state(const py::tuple& t) {
  const int version = t.size() > 0 && py::isinstance<py::int_>(t[0]) ? py::cast<int>(t[0]) : 0;
  if (!((version == 1 && t.size() == 8) || (version == 2 && t.size() == 9)))
    data_error(
        "not a Fit state (a tuple of 9 values, version 2, or 8, version 1, from "
        "Fit.__reduce__)");
  PyFit f;
  f.result.surface = io::surface_from_json_text(py::cast<std::string>(t[1]), "pickle");
  f.result.report = io::report_from_json_text(py::cast<std::string>(t[2]), "pickle");
  f.result.u = from_bytes<double>(t[3], "u");
  f.result.v = from_bytes<double>(t[4], "v");
  const std::vector<Point> points = from_bytes<Point>(t[5], "points");
  const auto sizes = py::cast<std::vector<long>>(t[6]);
  auto rows = std::make_shared<Rows>();
  std::size_t at = 0;
  for (long n : sizes) {
    if (n < 0 || at + static_cast<std::size_t>(n) > points.size())
      data_error("Fit state: row sizes and points disagree");
    rows->add_row({points.data() + at, static_cast<std::size_t>(n)});
    at += static_cast<std::size_t>(n);
  }
  if (at != points.size()) data_error("Fit state: row sizes and points disagree");
  std::vector<double> weights = from_bytes<double>(t[7], "weights");
  if (!weights.empty() && weights.size() != points.size())
    data_error("Fit state: weights and points disagree");
  rows->set_weights(std::move(weights));
  if (version == 2) {
    f.result.v_points = from_bytes<double>(t[8], "v_points");
    if (!f.result.v_points.empty() && f.result.v_points.size() != points.size())
      data_error("Fit state: v_points and points disagree");
  }
  f.rows = std::move(rows);
  return f;
}

Surface load_surface(const std::string& path) {
  check_path(path, "path");
  const std::string e = io::extension_of(path);
  py::gil_scoped_release nogil;
  if (e == "step" || e == "stp" || e == "iges" || e == "igs")
    return exchange::read_cad_surface(path);
  return io::read_surface_json(path);
}

}  // namespace

void bind_state(py::module_& m) {
  m.def(
      "_surface_from_state", [](py::handle state) { return surface_from_state(state); },
      py::arg("state"));
  m.def(
      "_fit_from_state", [](const py::tuple& state) { return fit_from_state(state); },
      py::arg("state"));
  py::object fit_class = m.attr("Fit");
  fit_class.attr("__reduce__") = py::cpp_function(
      [](const PyFit& f) {
        return py::make_tuple(py::module_::import("sfit._state").attr("fit_from_state"),
                              py::make_tuple(fit_state(f)));
      },
      py::name("__reduce__"), py::is_method(fit_class));
  fit_class.attr("__copy__") = py::cpp_function([](const PyFit& f) { return f; },
                                                py::name("__copy__"), py::is_method(fit_class));
  fit_class.attr("__deepcopy__") =
      py::cpp_function([](const PyFit& f, py::handle) { return f; }, py::name("__deepcopy__"),
                       py::is_method(fit_class), py::arg("memo"));
  m.def("load_surface", &load_surface, py::arg("path"),
        R"(Reads a surface: a .json written by sfit (docs/surface-json.md), or the one B-spline
face of a .step/.stp/.iges/.igs file (as Surface.save() writes them; this build's
OpenCASCADE reads it). Raises sfit.Error (file and reason).)");
}

}  // namespace sfit::python
