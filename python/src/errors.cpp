#include "errors.h"

#include "bindings.h"

namespace sfit::python {

void usage_error(const std::string& option, const std::string& message) {
  throw Error(ErrorCode::kUsage, message, Place{.option = option});
}

void data_error(const std::string& message, long row, long point) {
  throw Error(ErrorCode::kInputData, message, Place{.row = row, .point = point});
}

py::object to_python_error(const Error& e) {
  const Place& p = e.place();
  auto number = [](long v) -> py::object {
    if (v < 0) return py::none();
    return py::int_(v);
  };
  auto text = [](const std::string& s) -> py::object {
    if (s.empty()) return py::none();
    return py::str(s);
  };
  py::tuple values(e.values().size());
  for (std::size_t k = 0; k < e.values().size(); ++k) values[k] = py::float_(e.values()[k]);
  py::object cls = py::module_::import("sfit._errors").attr("Error");
  return cls(py::str(e.what()), py::arg("code") = to_string(e.code()),
             py::arg("exit_code") = e.exit_code(), py::arg("message") = e.message(),
             py::arg("file") = text(p.file), py::arg("line") = number(p.line),
             py::arg("column") = number(p.column), py::arg("row") = number(p.row),
             py::arg("index") = number(p.point), py::arg("option") = text(p.option),
             py::arg("values") = values);
}

void bind_errors(py::module_& m) {
  (void)m;
  py::register_exception_translator([](std::exception_ptr ep) {
    try {
      if (ep) std::rethrow_exception(ep);
    } catch (const Error& e) {
      py::object err = to_python_error(e);
      PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(err.ptr())), err.ptr());
    }
  });
}

}  // namespace sfit::python
