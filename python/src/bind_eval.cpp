// Evaluation of sfit.Surface from one basis pass per point (sfit/surface_eval.h): points,
// partial derivatives, normals, curvature, on a grid or pointwise; closest points;
// Surface.from_knots; Surface pickling (its state is the JSON text; bind_state.cpp reads it).
#include <pybind11/stl.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "errors.h"
#include "eval.h"
#include "sfit/fit_limits.h"
#include "sfit/io/surface_json.h"
#include "sfit/surface_eval.h"
#include "surface_json_value.h"

namespace sfit::python {
namespace {

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

// What one evaluation writes at each (u, v), and how many doubles.
enum class What { kPoint, kDerivative, kNormal, kDerivatives, kCurvature };

struct Request {
  What what = What::kPoint;
  int order = 0;       // of the derivatives needed
  int slot = 0;        // kDerivative: which of surface_derivatives()'s outputs
  int du = 0, dv = 0;  // kDerivative: the partial derivative
  std::vector<py::ssize_t> tail;
  std::size_t width() const {
    std::size_t w = 1;
    for (auto t : tail) w *= static_cast<std::size_t>(t);
    return w;
  }
};

void write(const Request& r, const Point* d, double* out) {
  switch (r.what) {
    case What::kPoint:
    case What::kDerivative:
      std::memcpy(out, d[r.slot].data(), 3 * sizeof(double));
      return;
    case What::kNormal: {
      const Point n = d[1].cross(d[2]);
      const double len = n.norm();
      const Point unit = len > 0 ? Point(n / len) : Point::Zero();
      std::memcpy(out, unit.data(), 3 * sizeof(double));
      return;
    }
    case What::kDerivatives:
      for (int k = 0; k < derivative_count(r.order); ++k)
        std::memcpy(out + 3 * k, d[k].data(), 3 * sizeof(double));
      return;
    case What::kCurvature: {
      const Curvature c = curvature_from(d);
      out[0] = c.gaussian;
      out[1] = c.mean;
      out[2] = c.k1;
      out[3] = c.k2;
      return;
    }
  }
}

py::array evaluate(const Surface& s, py::handle u_in, py::handle v_in, bool grid, const Request& r,
                   int threads) {
  check_threads(threads, "threads");
  bool u_scalar = false, v_scalar = false;
  const std::vector<double> u = parameters_from(u_in, "u", u_scalar);
  const std::vector<double> v = parameters_from(v_in, "v", v_scalar);
  const std::size_t w = r.width();
  if (grid) {
    std::vector<py::ssize_t> shape = {static_cast<py::ssize_t>(u.size()),
                                      static_cast<py::ssize_t>(v.size())};
    shape.insert(shape.end(), r.tail.begin(), r.tail.end());
    DoubleArray out(shape);
    double* p = out.mutable_data();
    const std::size_t nv = v.size();
    py::gil_scoped_release nogil;
    // Each direction's basis once; every (u_i, v_j) only combines them (the same bits as a
    // pointwise evaluation).
    const bool partial = r.what == What::kDerivative;
    const DirectionBasis bu = direction_basis(s, true, u, partial ? r.du : r.order);
    const DirectionBasis bv = direction_basis(s, false, v, partial ? r.dv : r.order);
    blocks(u.size() * nv, threads, [&](std::size_t k) {
      if (partial) {
        const Point q = surface_partial(s, bu, k / nv, bv, k % nv, r.du, r.dv);
        std::memcpy(p + k * w, q.data(), 3 * sizeof(double));
        return;
      }
      Point d[6];
      surface_derivatives(s, bu, k / nv, bv, k % nv, d);
      write(r, d, p + k * w);
    });
    return out;
  }
  const std::size_t n = std::max(u.size(), v.size());
  if (u.size() != v.size() && !(u_scalar || v_scalar))
    usage_error("v", "u and v must have the same length (got " + std::to_string(u.size()) +
                         " and " + std::to_string(v.size()) +
                         "), one must be a number, or use grid=True");
  const bool both = u_scalar && v_scalar;
  std::vector<py::ssize_t> shape;
  if (!both) shape.push_back(static_cast<py::ssize_t>(n));
  shape.insert(shape.end(), r.tail.begin(), r.tail.end());
  DoubleArray out(shape);
  double* p = out.mutable_data();
  {
    py::gil_scoped_release nogil;
    const bool ub = u.size() == 1 && u_scalar, vb = v.size() == 1 && v_scalar;
    blocks(both ? 1 : n, threads, [&](std::size_t k) {
      const double uu = u[ub ? 0 : k], vv = v[vb ? 0 : k];
      if (r.what == What::kPoint || r.what == What::kDerivative) {
        const Point q =
            r.what == What::kPoint ? s.evaluate(uu, vv) : surface_partial(s, uu, vv, r.du, r.dv);
        std::memcpy(p + k * w, q.data(), 3 * sizeof(double));
        return;
      }
      Point d[6];
      surface_derivatives(s, uu, vv, r.order, d);
      write(r, d, p + k * w);
    });
  }
  return out;
}

Request derivative_request(int du, int dv) {
  if (du < 0 || dv < 0 || du + dv > 2)
    usage_error(du < 0 || du + dv > 2 ? "du" : "dv",
                "derivatives of order du + dv <= 2 (du, dv >= 0), got du=" + std::to_string(du) +
                    ", dv=" + std::to_string(dv));
  static const int slot[3][3] = {{0, 2, 5}, {1, 4, -1}, {3, -1, -1}};
  return {What::kDerivative, du + dv, slot[du][dv], du, dv, {3}};
}

}  // namespace

void bind_surface_eval(py::class_<Surface>& c) {
  c.def(
       "__call__",
       [](const Surface& s, py::handle u, py::handle v, bool grid, int threads) {
         return evaluate(s, u, v, grid, {What::kPoint, 0, 0, 0, 0, {3}}, threads);
       },
       py::arg("u"), py::arg("v"), py::arg("grid") = false, py::arg("threads") = 0,
       R"(S(u, v).

u, v: numbers or 1-D arrays of the same length n (a number is repeated): an (n, 3) array
(a (3,) array for two numbers). grid=True: the grid u x v, an (len(u), len(v), 3) array
whose [i, j] is S(u[i], v[j]) (as SciPy's RectBivariateSpline: the first axis runs over u,
along the rows). threads: 0 uses all cores; the values do not depend on it.
Raises sfit.Error for non-finite parameters or mismatched lengths.)")
      .def(
          "derivative",
          [](const Surface& s, py::handle u, py::handle v, int du, int dv, bool grid, int threads) {
            return evaluate(s, u, v, grid, derivative_request(du, dv), threads);
          },
          py::arg("u"), py::arg("v"), py::arg("du") = 1, py::arg("dv") = 0, py::arg("grid") = false,
          py::arg("threads") = 0,
          "Partial derivative d^(du+dv) S / du^du dv^dv (du + dv <= 2), shaped as __call__.")
      .def(
          "derivatives",
          [](const Surface& s, py::handle u, py::handle v, int order, bool grid, int threads) {
            if (order < 0 || order > 2)
              usage_error("order", "0, 1 or 2, got " + std::to_string(order));
            return evaluate(s, u, v, grid,
                            {What::kDerivatives, order, 0, 0, 0, {derivative_count(order), 3}},
                            threads);
          },
          py::arg("u"), py::arg("v"), py::arg("order") = 1, py::arg("grid") = false,
          py::arg("threads") = 0,
          R"(S and its partial derivatives up to `order` from one basis evaluation per point.

Shaped as __call__ with one more axis before the last: [..., k, :] is S (k = 0), S_u (1),
S_v (2) and, for order 2, S_uu (3), S_uv (4), S_vv (5).)")
      .def(
          "normal",
          [](const Surface& s, py::handle u, py::handle v, bool grid, int threads) {
            return evaluate(s, u, v, grid, {What::kNormal, 1, 0, 0, 0, {3}}, threads);
          },
          py::arg("u"), py::arg("v"), py::arg("grid") = false, py::arg("threads") = 0,
          "Unit normal S_u x S_v / |S_u x S_v|, shaped as __call__; (0, 0, 0) where S_u x S_v "
          "vanishes (a pole).")
      .def(
          "_curvature",
          [](const Surface& s, py::handle u, py::handle v, bool grid, int threads) {
            return evaluate(s, u, v, grid, {What::kCurvature, 2, 0, 0, 0, {4}}, threads);
          },
          py::arg("u"), py::arg("v"), py::arg("grid") = false, py::arg("threads") = 0,
          "(gaussian, mean, k1, k2) in the last axis (Surface.curvature() names them).")
      .def(
          "closest_point",
          [](const Surface& s, py::handle points, int threads) -> py::object {
            check_threads(threads, "threads");
            DoubleArray a = DoubleArray::ensure(points);
            if (!a || !((a.ndim() == 1 && a.shape(0) == 3) || (a.ndim() == 2 && a.shape(1) == 3)))
              data_error("points must be 3 numbers or an (n, 3) array");
            const std::size_t n = a.ndim() == 1 ? 1 : static_cast<std::size_t>(a.shape(0));
            const auto* p = reinterpret_cast<const Point*>(a.data());
            for (std::size_t k = 0; k < n; ++k)
              if (!p[k].allFinite())
                throw Error(ErrorCode::kInputData,
                            "points[" + std::to_string(k) + "] is not finite",
                            Place{.point = static_cast<long>(k)});
            DoubleArray u(static_cast<py::ssize_t>(n)), v(static_cast<py::ssize_t>(n));
            double* pu = u.mutable_data();
            double* pv = v.mutable_data();
            {
              py::gil_scoped_release nogil;
              const ClosestPointFinder finder(s);
              blocks(n, threads, [&](std::size_t k) {
                const ClosestPoint c = finder.find(p[k]);
                pu[k] = c.u;
                pv[k] = c.v;
              });
            }
            if (a.ndim() == 1) return py::make_tuple(pu[0], pv[0]);
            return py::make_tuple(u, v);
          },
          py::arg("points"), py::arg("threads") = 0,
          R"((u, v) of the point of the surface nearest to each point: numbers for 3 numbers, two
(n,) arrays for an (n, 3) array; S(u, v) is that nearest point. Newton's method from the
nearest of a grid of samples of the surface, kept inside the domain of an open direction
(points beyond an edge or a corner find it), wrapped around a periodic one.)")
      .def_static(
          "from_knots",
          [](py::handle knots_u, py::handle knots_v, py::handle control_points, int degree_u,
             int degree_v, bool periodic_u, bool periodic_v) {
            nlohmann::json j;
            j["type"] = "bspline_surface";
            j["degree"] = {degree_u, degree_v};
            j["periodic"] = {periodic_u, periodic_v};
            bool scalar = false;
            j["knots_u"] = parameters_from(knots_u, "knots_u", scalar);
            j["knots_v"] = parameters_from(knots_v, "knots_v", scalar);
            DoubleArray cp = DoubleArray::ensure(control_points);
            if (!cp || cp.ndim() != 3 || cp.shape(2) != 3)
              data_error("control_points must be an (nu_full, nv_full, 3) array");
            nlohmann::json rows = nlohmann::json::array();
            for (py::ssize_t i = 0; i < cp.shape(0); ++i) {
              nlohmann::json row = nlohmann::json::array();
              for (py::ssize_t l = 0; l < cp.shape(1); ++l)
                row.push_back({cp.at(i, l, 0), cp.at(i, l, 1), cp.at(i, l, 2)});
              rows.push_back(std::move(row));
            }
            j["control_points"] = std::move(rows);
            return io::surface_from_json(j, "from_knots");
          },
          py::arg("knots_u"), py::arg("knots_v"), py::arg("control_points"), py::arg("degree_u"),
          py::arg("degree_v"), py::arg("periodic_u") = false, py::arg("periodic_v") = false,
          R"(The surface with these full knot vectors, (nu_full, nv_full, 3) control points and
degrees: the stored form Surface.knots_u, .knots_v, .control_points give back (a periodic
direction repeats its first `degree` control points, docs/surface-json.md). Knots may be
non-uniform: non-decreasing, interior knots repeated at most `degree` times, degree + 1 equal
knots at each end of an open direction, the spacing repeating with the period in a periodic
one (the domain is shifted to begin at 0); other vectors raise sfit.Error naming the vector.)")
      .def("__getstate__", [](const Surface& s) { return io::surface_to_json_text(s); })
      .def("__reduce__",
           [](const Surface& s) {
             return py::make_tuple(py::module_::import("sfit._state").attr("surface_from_state"),
                                   py::make_tuple(io::surface_to_json_text(s)));
           })
      .def("__copy__", [](const Surface& s) { return s; })
      .def(
          "__deepcopy__", [](const Surface& s, py::handle) { return s; }, py::arg("memo"));
  // pybind11 takes a method it binds under the name __setstate__ for a constructor, which
  // does nothing on an existing object (a silent no-op for any state): bind it under another
  // name and set the attribute.
  c.attr("__setstate__") = py::cpp_function(
      [](Surface& s, py::handle state) { s = surface_from_state(state); }, py::name("setstate"),
      py::is_method(c), py::arg("state"),
      "Replaces the surface by the one in `state` (the JSON text of __getstate__); raises "
      "sfit.Error for anything else, leaving the surface unchanged.");
}

}  // namespace sfit::python
