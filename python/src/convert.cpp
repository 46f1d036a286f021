#include "convert.h"

#include <cmath>
#include <cstring>

#include "errors.h"

namespace sfit::python {
namespace {

std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t k = 0; k < a.ndim(); ++k) s += (k ? ", " : "") + std::to_string(a.shape(k));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// `obj` as a C-ordered float64 array, from any integer or float dtype; sfit.Error otherwise.
DoubleArray numeric(py::handle obj, const std::string& what, long row) {
  py::array a = py::array::ensure(obj);
  if (!a) data_error(what + " is not an array of numbers (a ragged or non-numeric sequence?)", row);
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u' && kind != 'f')
    data_error(what + " must hold numbers (an integer or float dtype), got dtype " +
                   std::string(py::str(a.dtype())),
               row);
  // Copies unless already C-ordered float64; any integer or float dtype casts (uint64 and
  // long double too, which numpy's safe casting would refuse).
  DoubleArray d = DoubleArray::ensure(a);
  if (!d)
    data_error(what + ": cannot convert dtype " + std::string(py::str(a.dtype())) + " to float64",
               row);
  return d;
}

}  // namespace

std::vector<Point> points_from(py::handle points, const std::string& what, long row) {
  DoubleArray a = numeric(points, what, row);
  if (a.ndim() != 2 || a.shape(1) != 3)
    data_error(what + " must be an (N, 3) array of points, got shape " + shape_of(a), row);
  std::vector<Point> out(static_cast<std::size_t>(a.shape(0)));
  if (!out.empty())
    std::memcpy(static_cast<void*>(out.data()), a.data(), out.size() * sizeof(Point));
  return out;
}

Rows rows_from(py::handle rows) {
  Rows out;
  std::vector<double> weights;
  if (py::isinstance<py::array>(rows)) {
    DoubleArray a = numeric(rows, "rows", -1);
    if (a.ndim() != 3 || (a.shape(2) != 3 && a.shape(2) != 4))
      data_error(
          "rows must be an (M, N, 3) array (an (M, N, 4) array with weights) or a list of "
          "(N_j, 3) arrays, got an array of shape " +
          shape_of(a) + (a.ndim() == 2 ? " (one row: use fit_curve)" : ""));
    const auto m = static_cast<std::size_t>(a.shape(0)), n = static_cast<std::size_t>(a.shape(1));
    const auto c = static_cast<std::size_t>(a.shape(2));
    out.reserve(m * n, m);
    if (c == 3) {
      const auto* p = reinterpret_cast<const Point*>(a.data());
      for (std::size_t j = 0; j < m; ++j) out.add_row({p + j * n, n});
      return out;
    }
    std::vector<Point> row(n);
    for (std::size_t j = 0; j < m; ++j) {
      for (std::size_t k = 0; k < n; ++k) {
        const double* q = a.data() + (j * n + k) * 4;
        row[k] = Point(q[0], q[1], q[2]);
        weights.push_back(q[3]);
      }
      out.add_row(row);
    }
    out.set_weights(std::move(weights));
    return out;
  }
  if (py::isinstance<py::str>(rows) || !py::isinstance<py::sequence>(rows))
    data_error("rows must be a list of (N_j, 3) arrays or an (M, N, 3) array, got " +
               std::string(py::str(py::type::of(rows).attr("__name__"))));
  const auto seq = py::reinterpret_borrow<py::sequence>(rows);
  long columns = 0;  // 3, or 4 with weights: the same in every row
  for (std::size_t j = 0; j < seq.size(); ++j) {
    const std::string what = "rows[" + std::to_string(j) + "]";
    DoubleArray a = numeric(seq[j], what, static_cast<long>(j));
    if (a.ndim() == 2 && a.shape(1) == 4 && (columns == 0 || columns == 4)) {
      columns = 4;
      std::vector<Point> row(static_cast<std::size_t>(a.shape(0)));
      for (std::size_t k = 0; k < row.size(); ++k) {
        const double* q = a.data() + k * 4;
        row[k] = Point(q[0], q[1], q[2]);
        weights.push_back(q[3]);
      }
      out.add_row(row);
      continue;
    }
    if (columns == 4 || (a.ndim() == 2 && a.shape(1) == 4))
      data_error(what +
                     ": every row has 3 columns (x, y, z) or every row has 4 (x, y, z, w), "
                     "got shape " +
                     shape_of(a) + " after rows of " + std::to_string(columns ? columns : 3) +
                     " columns",
                 static_cast<long>(j));
    columns = 3;
    out.add_row(points_from(a, what, static_cast<long>(j)));
  }
  if (columns == 4) out.set_weights(std::move(weights));
  return out;
}

py::list rows_to_list_weighted(const Rows& rows) {
  if (!rows.weighted()) return rows_to_list(rows);
  py::list out;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const auto r = rows[j];
    const auto w = rows.row_weights(j);
    DoubleArray a({static_cast<py::ssize_t>(r.size()), py::ssize_t{4}});
    double* p = a.mutable_data();
    for (std::size_t k = 0; k < r.size(); ++k) {
      p[4 * k] = r[k].x();
      p[4 * k + 1] = r[k].y();
      p[4 * k + 2] = r[k].z();
      p[4 * k + 3] = w[k];
    }
    out.append(a);
  }
  return out;
}

Point point_from(py::handle p, const std::string& what) {
  DoubleArray a = numeric(p, what, -1);
  if (a.size() != 3 || a.ndim() != 1)
    data_error(what + " must be 3 numbers (x, y, z), got shape " + shape_of(a));
  return Point(a.at(0), a.at(1), a.at(2));
}

Point per_axis_from(py::handle v, const std::string& option) {
  py::array a = py::array::ensure(v);
  const char kind = a ? a.dtype().kind() : '?';
  if (!a || (kind != 'i' && kind != 'u' && kind != 'f') || (a.ndim() > 1) ||
      (a.size() != 1 && a.size() != 3))
    usage_error(option, "expected one number or three (Tx, Ty, Tz), got " +
                            std::string(py::str(py::repr(v))));
  DoubleArray d = numeric(a, option, -1);
  return d.size() == 1 ? Point::Constant(d.data()[0])
                       : Point(d.data()[0], d.data()[1], d.data()[2]);
}

std::vector<double> parameters_from(py::handle v, const std::string& what, bool& scalar) {
  DoubleArray a = numeric(v, what, -1);
  if (a.ndim() > 1)
    data_error(what + " must be a number or a 1-D array of parameters, got shape " + shape_of(a));
  scalar = a.ndim() == 0;
  std::vector<double> out(a.data(), a.data() + a.size());
  for (std::size_t k = 0; k < out.size(); ++k)
    if (!std::isfinite(out[k]))
      throw Error(ErrorCode::kInputData,
                  what + "[" + std::to_string(k) + "] is not a finite number", Place{}, {out[k]});
  return out;
}

DoubleArray points_to_array(const Point* points, std::size_t n) {
  DoubleArray a({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  if (n) std::memcpy(a.mutable_data(), points, n * sizeof(Point));
  return a;
}

DoubleArray vector_to_array(const std::vector<double>& v) {
  DoubleArray a(static_cast<py::ssize_t>(v.size()));
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(double));
  return a;
}

py::list rows_to_list(const Rows& rows) {
  py::list out;
  for (std::size_t j = 0; j < rows.size(); ++j)
    out.append(points_to_array(rows[j].data(), rows[j].size()));
  return out;
}

py::array read_only(py::array a) {
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

void check_path(const std::string& path, const std::string& option) {
  if (path.find('\0') != std::string::npos)
    usage_error(option, "the path contains a NUL character (at byte " +
                            std::to_string(path.find('\0')) + ")");
}

py::object json_to_python(const nlohmann::json& j) {
  using T = nlohmann::json::value_t;
  switch (j.type()) {
    case T::null:
      return py::none();
    case T::boolean:
      return py::bool_(j.get<bool>());
    case T::number_integer:
      return py::int_(j.get<long long>());
    case T::number_unsigned:
      return py::int_(j.get<unsigned long long>());
    case T::number_float:
      return py::float_(j.get<double>());
    case T::string:
      return py::str(j.get<std::string>());
    case T::array: {
      py::list l;
      for (const auto& e : j) l.append(json_to_python(e));
      return l;
    }
    case T::object: {
      py::dict d;
      for (const auto& [k, v] : j.items()) d[py::str(k)] = json_to_python(v);
      return d;
    }
    default:
      return py::none();
  }
}

}  // namespace sfit::python
