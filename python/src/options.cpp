#include "options.h"

#include <memory>
#include <sstream>
#include <vector>

#include "basis.h"
#include "convert.h"
#include "errors.h"
#include "progress.h"
#include "sfit/option_names.h"
#include "sfit/parametrization.h"

namespace sfit::python {
namespace {

int integer(py::handle v, const char* name) {
  if (py::isinstance<py::bool_>(v) || !PyIndex_Check(v.ptr()))
    usage_error(name, "expected an integer, got " + std::string(py::str(py::repr(v))));
  const long long x = PyLong_AsLongLong(v.ptr());  // calls __index__
  if (x == -1 && PyErr_Occurred()) {
    PyErr_Clear();
    usage_error(name, "expected an integer that fits, got " + std::string(py::str(py::repr(v))));
  }
  if (x < -2147483647LL || x > 2147483647LL)
    usage_error(name, "integer out of range: " + std::to_string(x));
  return static_cast<int>(x);
}

double number(py::handle v, const char* name) {
  if (py::isinstance<py::bool_>(v) || !PyNumber_Check(v.ptr()) || py::isinstance<py::str>(v))
    usage_error(name, "expected a number, got " + std::string(py::str(py::repr(v))));
  PyObject* f = PyNumber_Float(v.ptr());
  if (!f) {
    PyErr_Clear();
    usage_error(name, "expected a real number, got " + std::string(py::str(py::repr(v))));
  }
  return py::cast<double>(py::reinterpret_steal<py::object>(f));
}

std::string text(py::handle v, const char* name) {
  if (!py::isinstance<py::str>(v))
    usage_error(name, "expected a string, got " + std::string(py::str(py::repr(v))));
  return py::cast<std::string>(v);
}

std::vector<int> integers(py::handle v, const char* name) {
  if (py::isinstance<py::str>(v) || !py::isinstance<py::iterable>(v))
    usage_error(name, "expected a sequence of integers, got " + std::string(py::str(py::repr(v))));
  std::vector<int> out;
  for (py::handle e : py::reinterpret_borrow<py::iterable>(v)) out.push_back(integer(e, name));
  return out;
}

// A named value parsed by the library's own parser (bool parse(std::string_view, T&)).
template <class T>
void named(T& out, py::handle v, const char* name, bool (*parse)(std::string_view, T&),
           const char* known) {
  const std::string s = text(v, name);
  if (!parse(s, out)) usage_error(name, "'" + s + "' is not one of " + known);
}

std::string g(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

struct Field {
  const char* name;
  std::string doc;
  void (*set)(Settings&, py::handle, const char*);
};

// The table. Order matters only where one option refines another: `degree` sets both
// directions, `degree_u` / `degree_v` then override one.
const std::vector<Field>& fields() {
  static const std::vector<Field> table = {
      {"tol", "tolerance T: one number or three (Tx, Ty, Tz), absolute, >= 0 (0 interpolates)",
       [](Settings& s, py::handle v, const char* n) { s.tol = per_axis_from(v, n); }},
      {"tol_rel",
       "tolerance as a fraction 0 ... 1 of the bounding-box diagonal (default " +
           g(kDefaultToleranceFraction) + ")",
       [](Settings& s, py::handle v, const char* n) {
         s.tol_rel = number(v, n);
         check_tolerance_fraction(*s.tol_rel, n);
       }},
      {"degree", "degree in both directions, 1 ... " + std::to_string(kMaxDegree),
       [](Settings& s, py::handle v, const char* n) {
         s.options.degree_u = s.options.degree_v = integer(v, n);
       }},
      {"degree_u", "degree along the rows (overrides degree)",
       [](Settings& s, py::handle v, const char* n) { s.options.degree_u = integer(v, n); }},
      {"degree_v", "degree across the rows (overrides degree)",
       [](Settings& s, py::handle v, const char* n) { s.options.degree_v = integer(v, n); }},
      {"closed",
       "closed directions: '' or 'none', 'u' (rows are closed contours), 'v' (the rows "
       "form a closed sequence), 'uv'",
       [](Settings& s, py::handle v, const char* n) {
         const std::string c = text(v, n);
         if (!parse_closed(c, s.options.closed_u, s.options.closed_v))
           usage_error(n, "'" + c + "' is not one of u, v, uv, none");
       }},
      {"search", "count search: 'fast', 'linear' (the paper's), 'known' (take the count hints)",
       [](Settings& s, py::handle v, const char* n) {
         named(s.options.search, v, n, parse_count_search, "fast, linear, known");
       }},
      {"parameters",
       "how points get parameters: 'paper', 'uniform', 'chord', 'centripetal', "
       "'fewest' (tries the four, keeps the fewest control points)",
       [](Settings& s, py::handle v, const char* n) {
         named(s.options.parametrization, v, n, parse_parametrization,
               "paper, uniform, chord, centripetal, fewest");
       }},
      {"threads", "threads, 0: all cores (results do not depend on it)",
       [](Settings& s, py::handle v, const char* n) { s.options.threads = integer(v, n); }},
      {"row_count_hints", "counts to start each row's search from (a report's row_counts)",
       [](Settings& s, py::handle v, const char* n) {
         s.options.row_count_hints = integers(v, n);
       }},
      {"column_count_hints", "counts to start each column's search from (column_counts)",
       [](Settings& s, py::handle v, const char* n) {
         s.options.column_count_hints = integers(v, n);
       }},
      {"progress",
       "callable(sfit.FitProgress) called as the fit goes (phase, pairs tried, best so far, "
       "seconds; with the GIL); returning False stops the fit (sfit.Error 'cancelled')",
       [](Settings& s, py::handle v, const char* n) {
         if (!PyCallable_Check(v.ptr()))
           usage_error(n, "expected a callable, got " + std::string(py::str(py::repr(v))));
         s.options.progress = python_progress(v);
       }},
  };
  return table;
}

}  // namespace

Settings settings_from(const py::kwargs& kwargs) {
  Settings s;
  for (const Field& f : fields())
    if (kwargs.contains(f.name)) {
      py::object v = kwargs[f.name];
      if (!v.is_none()) f.set(s, v, f.name);
    }
  for (const auto& [key, value] : kwargs) {
    (void)value;
    const std::string k = py::cast<std::string>(key);
    bool known = false;
    std::string names;
    for (const Field& f : fields()) {
      known = known || k == f.name;
      names += (names.empty() ? "" : ", ") + std::string(f.name);
    }
    if (!known) usage_error(k, "unknown option (known: " + names + ")");
  }
  if (s.tol && s.tol_rel) usage_error("tol_rel", "give tol or tol_rel, not both");
  return s;
}

FitOptions resolve(const Rows& rows, const Settings& s) {
  FitOptions o = s.options;
  o.tolerance =
      s.tol ? *s.tol : relative_tolerance(rows, s.tol_rel.value_or(kDefaultToleranceFraction));
  return o;
}

std::string options_doc() {
  std::string out;
  for (const Field& f : fields()) out += "    " + std::string(f.name) + ": " + f.doc + "\n";
  return out;
}

}  // namespace sfit::python
