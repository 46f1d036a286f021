// sfit.load_rows(): every input format of `sfit fit`, through the library's readers
// (sfit/files.h): no CLI code, nothing printed.
#include "bindings.h"
#include "convert.h"
#include "sfit/files.h"

namespace sfit::python {

void bind_io(py::module_& m) {
  m.def(
      "load_rows",
      [](const std::string& path) {
        check_path(path, "path");
        files::Input in;
        {
          py::gil_scoped_release nogil;
          in = files::read_input(path);
        }
        return rows_to_list_weighted(in.rows);
      },
      py::arg("path"),
      R"(Reads rows of points from any input `sfit fit` reads (.rows, .srows, .csv, and the
section curves of .step/.iges where this build has them): a list of (N_j, 3) float64 arrays,
or (N_j, 4) arrays (x, y, z, w) when the file carries weights (every point then has one);
sfit.fit() takes either and fits the weighted rows as `sfit fit FILE` does.
Raises sfit.Error with file:line:column (codes input-unreadable, input-syntax, input-data).)");
}

}  // namespace sfit::python
