// sfit.Surface: the fitted B-spline surface, its evaluation (as SciPy's
// RectBivariateSpline: arrays in, arrays out, grid=True for u x v), saving and loading.
#include <pybind11/stl.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "errors.h"
#include "eval.h"
#include "options.h"
#include "sfit/files.h"
#include "sfit/io/formats.h"
#include "sfit/io/surface_json.h"
#include "surface_json_value.h"

namespace sfit::python {

void save_output(const std::string& path, const Surface& surface, const PyFit* fit,
                 const OutputSettings& out) {
  check_path(path, "path");
  files::check_output_extension(path);
  files::check_output_options(out.units, out.mesh_density, out.normals);
  files::OutputContext context{surface,
                               fit ? &fit->result : nullptr,
                               fit ? fit->rows.get() : nullptr,
                               "python",
                               out.mesh,
                               out.mesh_density,
                               out.fields,
                               out.units};
  context.obj_freeform = out.obj_freeform;
  context.normals = out.normals;
  py::gil_scoped_release nogil;
  files::write_output(path, context);
}

void bind_surface(py::module_& m) {
  py::class_<Surface> c(
      m, "Surface",
      R"(A tensor-product B-spline surface, on uniform knots unless fitted with non-uniform ones.

u runs along the rows, v across them. The parameter domain is [0, u_end] x [0, v_end];
evaluation clamps parameters into an open direction and wraps them around a periodic one.
The arrays are the stored form of docs/surface-json.md: full knot vectors, and control
points (nu + degree_u wrap copies in a periodic direction) as an (nu_full, nv_full, 3) array.)");
  c.def_property_readonly(
       "degree", [](const Surface& s) { return py::make_tuple(s.degree_u, s.degree_v); },
       "(degree_u, degree_v)")
      .def_readonly("degree_u", &Surface::degree_u)
      .def_readonly("degree_v", &Surface::degree_v)
      .def_property_readonly(
          "periodic", [](const Surface& s) { return py::make_tuple(s.periodic_u, s.periodic_v); },
          "(periodic_u, periodic_v): closed directions")
      .def_property_readonly(
          "count", [](const Surface& s) { return py::make_tuple(s.count_u, s.count_v); },
          "(nu, nv): distinct control points in each direction")
      .def_property_readonly(
          "knots_u", [](const Surface& s) { return read_only(vector_to_array(s.full_knots_u())); },
          "full knot vector along u (length nu_full + degree_u + 1), uniform or not")
      .def_property_readonly(
          "knots_v", [](const Surface& s) { return read_only(vector_to_array(s.full_knots_v())); },
          "full knot vector along v")
      .def_property_readonly(
          "control_points",
          [](const Surface& s) {
            const int fu = s.full_count_u(), fv = s.full_count_v();
            DoubleArray a({py::ssize_t{fu}, py::ssize_t{fv}, py::ssize_t{3}});
            auto* p = reinterpret_cast<Point*>(a.mutable_data());
            for (int i = 0; i < fu; ++i)
              for (int j = 0; j < fv; ++j)
                p[static_cast<std::size_t>(i) * fv + j] = s.full_at(i, j);
            return read_only(a);
          },
          "(nu_full, nv_full, 3) array: the stored form (wrap copies in a periodic direction)")
      .def_property_readonly(
          "uniform_knots",
          [](const Surface& s) { return py::make_tuple(s.knots_u.uniform(), s.knots_v.uniform()); },
          "(u, v): True where the knots are sfit's uniform ones")
      .def_property_readonly("u_end", &Surface::u_end, "end of the u domain [0, u_end]")
      .def_property_readonly("v_end", &Surface::v_end, "end of the v domain [0, v_end]")
      .def(
          "save",
          [](const Surface& s, const std::string& path, bool mesh, int mesh_density, bool fields,
             const std::string& units, bool obj_freeform, const std::string& normals) {
            save_output(path, s, nullptr,
                        output_settings(mesh, mesh_density, fields, units, obj_freeform, normals));
          },
          py::arg("path"), py::arg("mesh") = output_default("mesh"),
          py::arg("mesh_density") = output_default("mesh_density"),
          py::arg("fields") = output_default("fields"), py::arg("units") = output_default("units"),
          py::arg("obj_freeform") = output_default("obj_freeform"),
          py::arg("normals") = output_default("normals"),
          R"(Writes the surface to `path` in the format of its extension, as `sfit convert -o`
(sfit.output_formats() lists them), atomically. mesh, mesh_density, fields, units,
obj_freeform, normals: as the CLI's --mesh, --mesh-density, --fields, --units, --obj-freeform,
--normals (sfit.fit_options() group "output").)")
      .def(
          "to_json", [](const Surface& s) { return json_to_python(io::surface_to_json(s)); },
          "The surface as the dict of docs/surface-json.md.")
      .def("__repr__", [](const Surface& s) {
        return "<sfit.Surface degree " + std::to_string(s.degree_u) + " x " +
               std::to_string(s.degree_v) + ", " + std::to_string(s.count_u) + " x " +
               std::to_string(s.count_v) + " control points" +
               (s.periodic_u ? ", periodic u" : "") + (s.periodic_v ? ", periodic v" : "") + ">";
      });
  bind_surface_eval(c);

  m.def(
      "output_formats",
      [] {
        std::vector<std::string> out;  // the one format registry (sfit/io/formats.h)
        for (const io::Format& f : io::formats())
          if (f.kind == io::FormatKind::kSurface && f.writes && f.available)
            for (std::string_view e : f.extensions) out.emplace_back(e);
        return out;
      },
      "Extensions Surface.save() and Fit.save() accept in this build (those of `sfit fit -o`).");
}

}  // namespace sfit::python
