// sfit.fit(), sfit.Fit and sfit.IncrementalFit: the surface fit of rows and its report.
#include <pybind11/stl.h>

#include <cstdio>

#include "bindings.h"
#include "convert.h"
#include "errors.h"
#include "options.h"
#include "progress.h"
#include "sfit/incremental.h"
#include "sfit/io/surface_json.h"
#include "surface_json_value.h"

namespace sfit::python {
namespace {

std::string g(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", x);
  return b;
}

py::object report_dict(const FitReport& r) {
  return json_to_python(io::report_to_json(r));  // the JSON report's keys, whatever they are
}

// A row or point index of an edit: negative ones are refused (no Python-style wrap-around).
std::size_t at(long i, const char* name) {
  if (i < 0) usage_error(name, "must be >= 0, got " + std::to_string(i));
  return static_cast<std::size_t>(i);
}

py::object make_fit(FitResult result, std::shared_ptr<const Rows> rows) {
  PyFit f{std::move(result), std::move(rows)};
  check_within_tolerance(f);
  return py::cast(std::move(f));
}

class PyIncrementalFit {
 public:
  PyIncrementalFit(py::handle rows, const py::kwargs& kwargs) {
    Rows r = rows_from(rows);
    FitOptions o = resolve(r, settings_from(kwargs));
    py::gil_scoped_release nogil;
    fit_ = std::make_unique<IncrementalFit>(std::move(r), std::move(o));
  }
  py::object result() const {
    return make_fit(fit_->result(), std::make_shared<const Rows>(fit_->rows()));
  }
  template <class Edit>
  py::object edit(Edit e) {
    {
      py::gil_scoped_release nogil;
      e(*fit_);
    }
    return result();
  }
  const IncrementalFit& get() const { return *fit_; }

 private:
  std::unique_ptr<IncrementalFit> fit_;
};

const char* kFitDoc = R"(Fits one B-spline surface to rows of points within a per-axis tolerance.

rows: a list of (N_j, 3) arrays (rows may differ in length) or an (M, N, 3) array for a grid.
Any integer or float dtype, any memory order (a C-ordered float64 copy is made).
Keyword options (None or absent: the library's default, as `sfit fit`):
)";

const char* kFitDocEnd = R"(
Returns a Fit. The GIL is released while fitting; the result does not depend on `threads`.
Raises sfit.Error: code "usage" (an option), "input-data" (the rows: shape, dtype, a
non-finite coordinate naming row and index, too few rows), "tolerance-not-met".)";

}  // namespace

void check_within_tolerance(const PyFit& f) {
  const FitReport& r = f.result.report;
  if (r.within_tolerance) return;
  const Point& d = r.worst_deviation;
  const Error e(ErrorCode::kToleranceNotMet,
                "the surface misses the tolerance at row " + std::to_string(r.worst_row) +
                    " point " + std::to_string(r.worst_index) + " by (" + g(d.x()) + ", " +
                    g(d.y()) + ", " + g(d.z()) + ")",
                Place{.row = r.worst_row, .point = r.worst_index}, {d.x(), d.y(), d.z()});
  py::object err = to_python_error(e);
  err.attr("fit") = py::cast(f);
  PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(err.ptr())), err.ptr());
  throw py::error_already_set();
}

void bind_fit(py::module_& m) {
  py::class_<PyFit>(m, "Fit", "A fitted surface and what it achieved (returned by sfit.fit).")
      .def_property_readonly(
          "surface", [](const PyFit& f) -> const Surface& { return f.result.surface; },
          py::return_value_policy::reference_internal, "the fitted sfit.Surface")
      .def_property_readonly(
          "report", [](const PyFit& f) { return report_dict(f.result.report); },
          "dict with the keys of the JSON report (`sfit fit --report`, docs/surface-json.md)")
      .def_property_readonly(
          "u", [](const PyFit& f) { return read_only(vector_to_array(f.result.u)); },
          "parameter u of every data point, row after row (length: all points)")
      .def_property_readonly(
          "v", [](const PyFit& f) { return read_only(vector_to_array(f.result.v)); },
          "parameter v of every row (length: rows); parameters 'geometric': each row's mean "
          "v_points")
      .def_property_readonly(
          "v_points", [](const PyFit& f) { return read_only(vector_to_array(f.result.v_points)); },
          "parameter v of every data point, row after row, where the rule gives each point its "
          "own (parameters 'geometric'); empty for the row rules (the points of row j are at "
          "v[j])")
      .def_property_readonly(
          "points",
          [](const PyFit& f) {
            return read_only(points_to_array(f.rows->points().data(), f.rows->total_points()));
          },
          "the fitted points, row after row, as a (P, 3) array (P: all points)")
      .def_property_readonly(
          "row_sizes",
          [](const PyFit& f) {
            std::vector<long> n;
            for (std::size_t j = 0; j < f.rows->size(); ++j)
              n.push_back(static_cast<long>((*f.rows)[j].size()));
            return n;
          },
          "points in each row")
      .def(
          "save",
          [](const PyFit& f, const std::string& path, bool mesh, int mesh_density, bool fields,
             const std::string& units, bool obj_freeform, const std::string& normals) {
            save_output(path, f.result.surface, &f,
                        output_settings(mesh, mesh_density, fields, units, obj_freeform, normals));
          },
          py::arg("path"), py::arg("mesh") = output_default("mesh"),
          py::arg("mesh_density") = output_default("mesh_density"),
          py::arg("fields") = output_default("fields"), py::arg("units") = output_default("units"),
          py::arg("obj_freeform") = output_default("obj_freeform"),
          py::arg("normals") = output_default("normals"),
          "Writes the surface as `sfit fit -o path` does (a .json with the report; .vtk "
          "fields with the deviations), atomically.")
      .def("__repr__", [](const PyFit& f) {
        const FitReport& r = f.result.report;
        return "<sfit.Fit " + std::to_string(r.count_u) + " x " + std::to_string(r.count_v) +
               " control points, " + std::to_string(r.rows) + " rows, " + std::to_string(r.points) +
               " points, within tolerance: " + (r.within_tolerance ? "yes" : "no") + ">";
      });

  m.def(
      "fit",
      [](py::handle rows, py::object tol, py::kwargs kwargs) {
        if (!tol.is_none()) {
          if (kwargs.contains("tol")) usage_error("tol", "given twice");
          kwargs["tol"] = tol;
        }
        const Settings settings = settings_from(kwargs);
        auto r = std::make_shared<Rows>(rows_from(rows));
        FitOptions o = resolve(*r, settings);
        FitResult result;
        run_fit(o, [&] { result = fit_surface(*r, o); });  // Ctrl-C, progress (progress.h)
        return make_fit(std::move(result), std::move(r));
      },
      py::arg("rows"), py::arg("tol") = py::none(),
      (std::string(kFitDoc) + options_doc() + kFitDocEnd).c_str());

  py::class_<PyIncrementalFit>(m, "IncrementalFit",
                               R"(A fit that follows edits of its rows (sfit::IncrementalFit).

IncrementalFit(rows, **options) fits as sfit.fit(rows, **options); the tolerance is then
fixed (absolute). Each edit returns the Fit that sfit.fit() gives for the edited rows with
that tolerance, bit for bit, refitting only what the edit touches. A bad edit raises
sfit.Error and leaves the state unchanged.)")
      .def(py::init([](py::handle rows, const py::kwargs& kwargs) {
             return std::make_unique<PyIncrementalFit>(rows, kwargs);
           }),
           py::arg("rows"))
      .def_property_readonly("fit", &PyIncrementalFit::result, "the current Fit")
      .def_property_readonly(
          "rows", [](const PyIncrementalFit& f) { return rows_to_list(f.get().rows()); },
          "the current rows, a list of (N_j, 3) arrays")
      .def_property_readonly(
          "rows_refitted", [](const PyIncrementalFit& f) { return f.get().rows_refitted(); },
          "rows whose curve stage the last edit refitted")
      .def(
          "move_point",
          [](PyIncrementalFit& f, long row, long index, py::handle to) {
            const Point p = point_from(to, "to");
            return f.edit(
                [&](IncrementalFit& i) { i.move_point(at(row, "row"), at(index, "index"), p); });
          },
          py::arg("row"), py::arg("index"), py::arg("to"), "Moves point `index` of `row`.")
      .def(
          "insert_point",
          [](PyIncrementalFit& f, long row, long index, py::handle point) {
            const Point p = point_from(point, "point");
            return f.edit(
                [&](IncrementalFit& i) { i.insert_point(at(row, "row"), at(index, "index"), p); });
          },
          py::arg("row"), py::arg("index"), py::arg("point"),
          "Inserts `point` before point `index` of `row` (index = row size appends).")
      .def(
          "erase_point",
          [](PyIncrementalFit& f, long row, long index) {
            return f.edit(
                [&](IncrementalFit& i) { i.erase_point(at(row, "row"), at(index, "index")); });
          },
          py::arg("row"), py::arg("index"), "Deletes point `index` of `row`.")
      .def(
          "replace_row",
          [](PyIncrementalFit& f, long row, py::handle points) {
            const std::vector<Point> p = points_from(points, "points", static_cast<long>(row));
            return f.edit([&](IncrementalFit& i) { i.replace_row(at(row, "row"), p); });
          },
          py::arg("row"), py::arg("points"), "Replaces `row` by an (N, 3) array of points.");
}

}  // namespace sfit::python
