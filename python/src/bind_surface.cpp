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
#include "options.h"
#include "sfit/files.h"
#include "sfit/io/formats.h"
#include "sfit/io/surface_json.h"
#include "surface_json_value.h"

namespace sfit::python {
namespace {

// What one evaluation writes at each (u, v): the point, a partial derivative, or the normal.
enum class What { kPoint, kDerivative, kNormal };

// Calls f(k) for k in [0, n) on `threads` threads (0: all cores) in contiguous blocks; each k
// is computed by one thread into its own slot, so the result does not depend on the count.
template <class F>
void blocks(std::size_t n, int threads, F f) {
  int t =
      threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  t = static_cast<int>(std::min<std::size_t>(t, n / 16384 + 1));  // not worth a thread below
  if (t <= 1) {
    for (std::size_t k = 0; k < n; ++k) f(k);
    return;
  }
  std::vector<std::thread> pool;
  const std::size_t step = (n + t - 1) / t;
  for (int i = 1; i < t; ++i)
    pool.emplace_back([&, i] {
      for (std::size_t k = i * step; k < std::min(n, (i + 1) * step); ++k) f(k);
    });
  for (std::size_t k = 0; k < std::min(n, step); ++k) f(k);
  for (auto& th : pool) th.join();
}

Point normal_at(const Surface& s, double u, double v) {
  Point d[6];
  s.derivatives(u, v, d);
  const Point n = d[1].cross(d[2]);
  const double len = n.norm();
  return len > 0 ? Point(n / len) : Point::Zero();
}

int derivative_slot(int du, int dv) {
  if (du < 0 || dv < 0 || du + dv > 2)
    usage_error(du < 0 || du + dv > 2 ? "du" : "dv",
                "derivatives of order du + dv <= 2 (du, dv >= 0), got du=" + std::to_string(du) +
                    ", dv=" + std::to_string(dv));
  static const int slot[3][3] = {{0, 2, 5}, {1, 4, -1}, {3, -1, -1}};
  return slot[du][dv];
}

py::array evaluate(const Surface& s, py::handle u_in, py::handle v_in, bool grid, What what,
                   int slot, int threads) {
  bool u_scalar = false, v_scalar = false;
  const std::vector<double> u = parameters_from(u_in, "u", u_scalar);
  const std::vector<double> v = parameters_from(v_in, "v", v_scalar);
  auto at = [&](double uu, double vv) -> Point {
    switch (what) {
      case What::kPoint:
        return s.evaluate(uu, vv);
      case What::kNormal:
        return normal_at(s, uu, vv);
      case What::kDerivative:
        break;
    }
    Point d[6];
    s.derivatives(uu, vv, d);
    return d[slot];
  };
  if (grid) {
    DoubleArray out(
        {static_cast<py::ssize_t>(u.size()), static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
    auto* p = reinterpret_cast<Point*>(out.mutable_data());
    const std::size_t nv = v.size();
    py::gil_scoped_release nogil;
    blocks(u.size() * nv, threads, [&](std::size_t k) { p[k] = at(u[k / nv], v[k % nv]); });
    return out;
  }
  const std::size_t n = std::max(u.size(), v.size());
  if (u.size() != v.size() && !(u_scalar || v_scalar))
    usage_error("v", "u and v must have the same length (got " + std::to_string(u.size()) +
                         " and " + std::to_string(v.size()) +
                         "), one must be a number, or use grid=True");
  DoubleArray out({static_cast<py::ssize_t>(u_scalar && v_scalar ? 1 : n), py::ssize_t{3}});
  auto* p = reinterpret_cast<Point*>(out.mutable_data());
  {
    py::gil_scoped_release nogil;
    const bool ub = u.size() == 1 && u_scalar, vb = v.size() == 1 && v_scalar;
    blocks(u_scalar && v_scalar ? 1 : n, threads,
           [&](std::size_t k) { p[k] = at(u[ub ? 0 : k], v[vb ? 0 : k]); });
  }
  if (u_scalar && v_scalar) return out.reshape({3});
  return out;
}

}  // namespace

void save_output(const std::string& path, const Surface& surface, const PyFit* fit,
                 const OutputSettings& out) {
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
  py::class_<Surface> c(m, "Surface", R"(A tensor-product B-spline surface on uniform knots.

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
          "knots_u", [](const Surface& s) { return vector_to_array(s.full_knots_u()); },
          "full knot vector along u (length nu_full + degree_u + 1)")
      .def_property_readonly(
          "knots_v", [](const Surface& s) { return vector_to_array(s.full_knots_v()); },
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
            return a;
          },
          "(nu_full, nv_full, 3) array: the stored form (wrap copies in a periodic direction)")
      .def_property_readonly("u_end", &Surface::u_end, "end of the u domain [0, u_end]")
      .def_property_readonly("v_end", &Surface::v_end, "end of the v domain [0, v_end]")
      .def(
          "__call__",
          [](const Surface& s, py::handle u, py::handle v, bool grid, int threads) {
            return evaluate(s, u, v, grid, What::kPoint, 0, threads);
          },
          py::arg("u"), py::arg("v"), py::arg("grid") = false, py::arg("threads") = 0,
          R"(S(u, v).

u, v: numbers or 1-D arrays of the same length n (a number is repeated): an (n, 3) array
(a (3,) array for two numbers). grid=True: the grid u x v, an (len(u), len(v), 3) array
(as SciPy's RectBivariateSpline). threads: 0 uses all cores; the values do not depend on it.
Raises sfit.Error for non-finite parameters or mismatched lengths.)")
      .def(
          "derivative",
          [](const Surface& s, py::handle u, py::handle v, int du, int dv, bool grid, int threads) {
            return evaluate(s, u, v, grid, What::kDerivative, derivative_slot(du, dv), threads);
          },
          py::arg("u"), py::arg("v"), py::arg("du") = 1, py::arg("dv") = 0, py::arg("grid") = false,
          py::arg("threads") = 0,
          "Partial derivative d^(du+dv) S / du^du dv^dv (du + dv <= 2), shaped as __call__.")
      .def(
          "normal",
          [](const Surface& s, py::handle u, py::handle v, bool grid, int threads) {
            return evaluate(s, u, v, grid, What::kNormal, 0, threads);
          },
          py::arg("u"), py::arg("v"), py::arg("grid") = false, py::arg("threads") = 0,
          "Unit normal S_u x S_v / |S_u x S_v|, shaped as __call__; (0, 0, 0) where S_u x S_v "
          "vanishes (a pole).")
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
      .def("__repr__",
           [](const Surface& s) {
             return "<sfit.Surface degree " + std::to_string(s.degree_u) + " x " +
                    std::to_string(s.degree_v) + ", " + std::to_string(s.count_u) + " x " +
                    std::to_string(s.count_v) + " control points" +
                    (s.periodic_u ? ", periodic u" : "") + (s.periodic_v ? ", periodic v" : "") +
                    ">";
           })
      .def(py::pickle([](const Surface& s) { return io::surface_to_json(s).dump(); },
                      [](const std::string& text) {
                        return io::surface_from_json(nlohmann::json::parse(text), "pickle");
                      }));

  m.def(
      "load_surface",
      [](const std::string& path) {
        py::gil_scoped_release nogil;
        return io::read_surface_json(path);
      },
      py::arg("path"), "Reads a surface file (.json, docs/surface-json.md) written by sfit.");
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
