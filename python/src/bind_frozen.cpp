// sfit.FrozenRefit: the refit at a finished fit's frozen counts, knots and parameters
// (sfit/frozen_refit.h), as the editor refits a drag: factorised once, then one solve per
// refit; a point's influence on the control points.
#include <pybind11/stl.h>

#include <memory>
#include <string>

#include "bindings.h"
#include "convert.h"
#include "sfit/error.h"
#include "sfit/frozen_refit.h"

namespace sfit::python {

void bind_frozen(py::module_& m) {
  py::class_<FrozenRefit, std::shared_ptr<FrozenRefit>>(
      m, "FrozenRefit",
      "Least squares at the counts, knots and parameters of a finished fit, frozen: refit() "
      "of rows of the same sizes costs one solve; influence() is a point's effect on the "
      "control points (the refit is linear in the data).")
      .def(py::init([](const PyFit& fit) {
             std::string why;
             auto f = FrozenRefit::make(*fit.rows, fit.result, why);
             if (!f)
               throw Error(ErrorCode::kUsage, "no frozen refit of this fit: " + why,
                           Place{.option = "fit"});
             return std::const_pointer_cast<FrozenRefit>(f);
           }),
           py::arg("fit"),
           "The frozen problem of `fit` (an sfit.Fit); sfit.Error where it "
           "cannot be made (weighted rows, rows the fit reordered, too many control points).")
      .def(
          "refit",
          [](const FrozenRefit& f, py::handle rows) {
            auto r = std::make_shared<Rows>(rows_from(rows));
            FitResult result = f.refit(*r);
            return PyFit{std::move(result), std::move(r)};
          },
          py::arg("rows"),
          "The least-squares sfit.Fit of `rows` (as many rows as the fit's, each as long) at the "
          "frozen counts, knots and parameters, every point checked against T: "
          "report['within_tolerance'] as a fit's.")
      .def(
          "influence",
          [](const FrozenRefit& f, std::size_t row, std::size_t index) {
            const std::vector<double> g = f.influence(row, index);
            return read_only(vector_to_array(g));
          },
          py::arg("row"), py::arg("index"),
          "The control points' motion per unit motion of point `index` of row `row`: one "
          "number per distinct control point (count_u * count_v, u-major: i * count_v + j).")
      .def_property_readonly("seconds", &FrozenRefit::seconds,
                             "seconds spent making it (assembly and factorisation)");
}

}  // namespace sfit::python
