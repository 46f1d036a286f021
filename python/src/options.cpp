#include "options.h"

#include <memory>
#include <vector>

#include "basis.h"
#include "convert.h"
#include "errors.h"
#include "progress.h"
#include "sfit/error.h"
#include "sfit/option_names.h"
#include "sfit/options.h"
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

// The library's value of a Python object for an option of the table's `type`.
OptionValue value_of(const OptionSpec& spec, py::handle v, const char* name) {
  switch (spec.type) {
    case OptionType::kInteger:
      return static_cast<long long>(integer(v, name));
    case OptionType::kNumber:
      return number(v, name);
    case OptionType::kTolerance:
      return per_axis_from(v, name);
    case OptionType::kChoice:
      return text(v, name);
    case OptionType::kFlag:
      if (!py::isinstance<py::bool_>(v))
        usage_error(name, "expected True or False, got " + std::string(py::str(py::repr(v))));
      return v.cast<bool>();
  }
  return false;
}

// The Python value of a table default (None where it depends on the data).
py::object default_of(const OptionSpec& s) {
  const std::string d(s.default_value);
  if (d.empty()) return py::none();
  switch (s.type) {
    case OptionType::kInteger:
      return py::int_(std::stoll(d));
    case OptionType::kNumber:
      return py::float_(std::stod(d));
    case OptionType::kFlag:
      return py::bool_(d == "true");
    default:
      return py::str(d);
  }
}

struct Extra {
  const char* name;
  const char* doc;
  void (*set)(Settings&, py::handle, const char*);
};

// The keywords of the Python module only (not options of `sfit fit`): count hints from an
// earlier report, and a progress callback.
const std::vector<Extra>& extras() {
  static const std::vector<Extra> table = {
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

std::string known_keywords() {
  std::string names;
  for (const OptionSpec& s : option_table())
    if (s.group == OptionGroup::kFit) names += (names.empty() ? "" : ", ") + std::string(s.name);
  for (const Extra& e : extras()) names += ", " + std::string(e.name);
  return names;
}

}  // namespace

Settings settings_from(const py::kwargs& kwargs) {
  Settings s;
  // The table's order: `degree` sets both directions, `degree_u` / `degree_v` then override.
  for (const OptionSpec& spec : option_table()) {
    if (spec.group != OptionGroup::kFit) continue;
    const std::string name(spec.name);
    if (!kwargs.contains(name.c_str())) continue;
    py::object v = kwargs[name.c_str()];
    if (v.is_none()) continue;
    set_fit_option(s, name, value_of(spec, v, name.c_str()), name);
  }
  for (const Extra& e : extras())
    if (kwargs.contains(e.name)) {
      py::object v = kwargs[e.name];
      if (!v.is_none()) e.set(s, v, e.name);
    }
  for (const auto& [key, value] : kwargs) {
    (void)value;
    const std::string k = py::cast<std::string>(key);
    const OptionSpec* spec = find_option(k);
    bool known = spec && spec->group == OptionGroup::kFit;
    for (const Extra& e : extras()) known = known || k == e.name;
    if (!known)
      usage_error(
          k, spec ? "an option of save(), not of the fit (fit options: " + known_keywords() + ")"
                  : "unknown option (known: " + known_keywords() + ")");
  }
  if (s.tol && s.tol_rel) usage_error("tol_rel", "give tol or tol_rel, not both");
  return s;
}

FitOptions resolve(const Rows& rows, const Settings& s) {
  FitOptions o = s.options;
  o.tolerance = s.tolerance(rows);
  return o;
}

std::string options_doc() {
  std::string out;
  for (const OptionSpec& s : option_table())
    if (s.group == OptionGroup::kFit) {
      std::string h = full_help(s);
      if (s.type == OptionType::kChoice) h += "; one of " + choice_list(s);
      out += "    " + std::string(s.name) + ": " + h + "\n";
    }
  for (const Extra& e : extras()) out += "    " + std::string(e.name) + ": " + e.doc + "\n";
  return out;
}

py::list fit_options() {
  py::list out;
  for (const OptionSpec& s : option_table()) {
    py::dict d;
    d["name"] = std::string(s.name);
    d["flag"] = std::string(s.flag);
    d["group"] = std::string(to_string(s.group));
    d["type"] = std::string(to_string(s.type));
    d["default"] = default_of(s);
    if (s.type == OptionType::kInteger) {
      d["min"] = static_cast<long long>(s.min);
      d["max"] = static_cast<long long>(s.max);
    } else if (s.type == OptionType::kNumber) {
      d["min"] = s.min;
      d["max"] = s.max;
    }
    if (s.type == OptionType::kChoice) {
      py::list c;
      for (std::string_view v : s.choices) c.append(std::string(v));
      d["choices"] = c;
    }
    d["help"] = s.help;
    out.append(d);
  }
  return out;
}

OutputSettings output_settings(bool mesh, int mesh_density, bool fields, const std::string& units,
                               bool obj_freeform, const std::string& normals) {
  OutputSettings o;
  set_output_option(o, "mesh", mesh, "mesh");
  set_output_option(o, "mesh_density", static_cast<long long>(mesh_density), "mesh_density");
  set_output_option(o, "fields", fields, "fields");
  set_output_option(o, "units", units, "units");
  set_output_option(o, "obj_freeform", obj_freeform, "obj_freeform");
  set_output_option(o, "normals", normals, "normals");
  return o;
}

py::object output_default(const char* name) {
  return default_of(*find_option(name));
}

void bind_options(py::module_& m) {
  m.def("fit_options", &fit_options,
        R"(The library's option table, one dict per option of `sfit fit`: name (the keyword of
fit() for group "fit", of save() for group "output"), flag (the CLI's), group, type ("integer",
"number", "tolerance", "choice", "flag"), default (None where it depends on the data), min and
max (integer, number), choices (choice), help. docs/options.md is made from the same table.)");
}

}  // namespace sfit::python
