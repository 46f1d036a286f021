// numpy arrays to sfit's points and rows and back. Every input array is checked and
// converted here: numbers of any integer or float dtype are taken as float64 (a copy in C
// order, so Fortran-ordered and strided arrays are accepted); other dtypes and wrong shapes
// raise sfit.Error naming the argument and the row. Non-finite coordinates are left to the
// library's validation (which names the row and point).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sfit/rows.h"

namespace sfit::python {

namespace py = pybind11;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// `rows`: a sequence of (N_j, 3) arrays (rows may differ in length) or an (M, N, 3) array;
/// with a fourth column (N_j, 4) / (M, N, 4) in every row, that column is the points' weights.
Rows rows_from(py::handle rows);
/// One row: an (N, 3) array; `what` names it in messages ("points", "rows[3]").
std::vector<Point> points_from(py::handle points, const std::string& what, long row = -1);
/// Three numbers (x, y, z).
Point point_from(py::handle p, const std::string& what);
/// A per-axis quantity: one number (all axes) or three.
Point per_axis_from(py::handle v, const std::string& option);
/// Parameters: a number or a 1-D array of finite numbers; `scalar` tells which it was.
std::vector<double> parameters_from(py::handle v, const std::string& what, bool& scalar);

/// (n, 3) float64 array of `n` points.
DoubleArray points_to_array(const Point* points, std::size_t n);
/// 1-D float64 array.
DoubleArray vector_to_array(const std::vector<double>& v);
/// The rows as a list of (N_j, 3) arrays.
py::list rows_to_list(const Rows& rows);
/// The same, with the weights as a fourth column (N_j, 4) when the rows carry weights.
py::list rows_to_list_weighted(const Rows& rows);
/// `a` made read-only (numpy writeable=False): for arrays that are copies of an object's state,
/// where a write would be lost.
py::array read_only(py::array a);
/// A path argument: refuses one with a NUL character (sfit.Error, code "usage", option `option`).
void check_path(const std::string& path, const std::string& option);
/// A JSON value as Python objects (dict, list, float, int, bool, str, None).
py::object json_to_python(const nlohmann::json& j);

}  // namespace sfit::python
