// sfit.fit_curve() and sfit.Curve: the curve stage on one row (sfit/curve_fit.h).
#include <pybind11/stl.h>

#include "bindings.h"
#include "convert.h"
#include "errors.h"
#include "sfit/curve_fit.h"
#include "sfit/option_names.h"
#include "sfit/parametrization.h"

namespace sfit::python {
namespace {

py::array curve_at(const Curve& c, py::handle t_in, int order) {
  bool scalar = false;
  const std::vector<double> t = parameters_from(t_in, "t", scalar);
  if (order < 0) usage_error("order", "must be >= 0, got " + std::to_string(order));
  std::vector<Point> out(t.size());
  {
    py::gil_scoped_release nogil;
    for (std::size_t k = 0; k < t.size(); ++k)
      out[k] = order == 0 ? c.evaluate(t[k]) : c.derivative(t[k], order);
  }
  DoubleArray a = points_to_array(out.data(), out.size());
  if (scalar) return a.reshape({3});
  return a;
}

}  // namespace

void bind_curve(py::module_& m) {
  py::class_<Curve>(m, "Curve", R"(A B-spline curve on uniform knots, open (clamped) or periodic.

Parameter domain [0, t_end]; evaluation clamps (open) or wraps (periodic) t.)")
      .def_readonly("degree", &Curve::degree)
      .def_readonly("periodic", &Curve::periodic)
      .def_property_readonly("count", &Curve::count, "distinct control points")
      .def_property_readonly("t_end", &Curve::domain_end, "end of the domain [0, t_end]")
      .def_property_readonly(
          "knots", [](const Curve& c) { return read_only(vector_to_array(c.knots())); },
          "full knot vector")
      .def_property_readonly(
          "control_points",
          [](const Curve& c) {
            std::vector<Point> full = c.control;
            if (c.periodic)
              for (int k = 0; k < c.degree; ++k) full.push_back(c.control[k % c.count()]);
            return read_only(points_to_array(full.data(), full.size()));
          },
          "(count + degree if periodic else count, 3): stored form with the wrap copies")
      .def(
          "__call__", [](const Curve& c, py::handle t) { return curve_at(c, t, 0); }, py::arg("t"),
          "C(t) for a number (a (3,) array) or a 1-D array (an (n, 3) array).")
      .def(
          "derivative",
          [](const Curve& c, py::handle t, int order) { return curve_at(c, t, order); },
          py::arg("t"), py::arg("order") = 1, "The order-th derivative dC/dt, shaped as __call__.")
      .def("__repr__", [](const Curve& c) {
        return "<sfit.Curve degree " + std::to_string(c.degree) + ", " + std::to_string(c.count()) +
               " control points" + (c.periodic ? ", periodic" : "") + ">";
      });

  py::class_<CurveFit>(m, "CurveFit", "A fitted curve and what it achieved (sfit.fit_curve).")
      .def_readonly("curve", &CurveFit::curve)
      .def_property_readonly(
          "parameters", [](const CurveFit& f) { return read_only(vector_to_array(f.parameters)); },
          "parameter t of each point")
      .def_property_readonly(
          "max_deviation",
          [](const CurveFit& f) {
            return read_only(points_to_array(&f.max_deviation, 1).reshape({3}));
          },
          "max |C(t_j) - D_j| per axis")
      .def_readonly("solves", &CurveFit::solves, "least-squares solves of the count search")
      .def_readonly("scaled", &CurveFit::scaled,
                    "True: parameters from the positions of `parameters`; False: the paper's");

  m.def(
      "fit_curve",
      [](py::handle points, py::object tol, int degree, bool closed, const std::string& search,
         const std::string& parameters, int hint) {
        const std::vector<Point> p = points_from(points, "points");
        CurveFitOptions o;
        o.degree = degree;
        o.periodic = closed;
        o.hint = hint;
        if (!parse_count_search(search, o.search))
          usage_error("search", "'" + search + "' is not one of fast, linear, known");
        Parametrization rule = Parametrization::kPaper;
        if (!parse_parametrization(parameters, rule) || rule == Parametrization::kFewest ||
            rule == Parametrization::kGeometric)
          usage_error("parameters",
                      "'" + parameters + "' is not one of paper, uniform, chord, centripetal");
        validate_curve(p, o);  // the points and degree, before they are used
        if (tol.is_none()) {
          Rows one;
          one.add_row(p);
          o.bound = relative_tolerance(one, kDefaultToleranceFraction);
        } else {
          o.bound = per_axis_from(tol, "tol");
        }
        std::vector<double> positions;
        if (rule != Parametrization::kPaper && !p.empty())
          positions = normalized_positions(p, rule, closed);
        o.positions = positions;
        validate_curve(p, o);
        py::gil_scoped_release nogil;
        return fit_curve(p, o);
      },
      py::arg("points"), py::arg("tol") = py::none(), py::arg("degree") = 3,
      py::arg("closed") = false, py::arg("search") = "fast", py::arg("parameters") = "paper",
      py::arg("hint") = 0,
      R"(Fits one row: the curve with the fewest control points whose every point is within
`tol` per axis (one number or three; default 1e-3 of the row's bounding-box diagonal).

points: an (N, 3) array. closed: the row is a closed contour (first point not repeated).
search: 'fast', 'linear', 'known' (take `hint` as the count). parameters: 'paper',
'uniform', 'chord', 'centripetal'. Returns a CurveFit. Raises sfit.Error.)");
}

}  // namespace sfit::python
