// sfit::Error as the Python exception sfit.Error (a ValueError; python/sfit/_errors.py).
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "sfit/error.h"

namespace sfit::python {

/// Throws sfit::Error(kUsage) naming the keyword `option` of a Python call.
[[noreturn]] void usage_error(const std::string& option, const std::string& message);
/// Throws sfit::Error(kInputData) about Python input (rows, points, parameters); `row` >= 0
/// names the row.
[[noreturn]] void data_error(const std::string& message, long row = -1, long point = -1);

/// The Python sfit.Error instance for `e` (not raised); `extra` attributes are set on it.
pybind11::object to_python_error(const Error& e);

}  // namespace sfit::python
