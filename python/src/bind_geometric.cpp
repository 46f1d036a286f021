// The pieces of the distributed fit at parameters "geometric" (python/sfit/_dask_geometric.py,
// docs/python.md "More than one machine"), each the library's own code for one chunk of points
// or for the client's step: the base plane from gathered statistics (sheet_frame()), each
// chunk's positions on it (sheet_positions()), its part of the scattered normal equations
// (scattered_add()), the solve with the smoothness term (scattered_solve()), the check of its
// points and the knot spans they cover, and the parameter correction (project_parameters()).
// Private (underscore names); plain numpy arrays in and out.
//
// A chunk here is an (m, 4) array (x, y, z, row), uncentred; `fuv` the (m, 2) fractions of
// its points (u, v in [0, 1]), which stay on the worker that holds the chunk.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "errors.h"
#include "geometric_params.h"
#include "geometric_search.h"
#include "knots.h"
#include "scattered_lsq.h"
#include "sfit/fold_check.h"

namespace sfit::python {
namespace {

using detail::ScatteredSpec;

ScatteredSpec spec_of(int degree_u, int degree_v, bool closed_u, bool closed_v) {
  if (closed_v)
    usage_error("closed", "parameters geometric: rows closed across have no base surface");
  return ScatteredSpec{degree_u, degree_v, closed_u, closed_v, 1};
}

// The chunk's points less the centre (as the in-memory fit's frame centres them).
std::vector<Point> centred_points(const DoubleArray& block, const Point& centre) {
  if (block.ndim() != 2 || block.shape(1) != 4)
    usage_error("points", "a chunk must be an (m, 4) array (x, y, z, row)");
  const std::size_t m = static_cast<std::size_t>(block.shape(0));
  std::vector<Point> out(m);
  const double* q = block.data();
  for (std::size_t k = 0; k < m; ++k, q += 4) out[k] = Point(q[0], q[1], q[2]) - centre;
  return out;
}

void fractions_of(const DoubleArray& fuv, std::size_t m, std::vector<double>& fu,
                  std::vector<double>& fv) {
  if (fuv.ndim() != 2 || fuv.shape(1) != 2 || static_cast<std::size_t>(fuv.shape(0)) != m)
    usage_error("fuv", "expected an (m, 2) array of fractions, one row per point of the chunk");
  fu.resize(m);
  fv.resize(m);
  for (std::size_t k = 0; k < m; ++k) {
    fu[k] = fuv.data()[2 * k];
    fv[k] = fuv.data()[2 * k + 1];
  }
}

// The centred surface of an (nu, nv, 3) array of control points, as scattered_solve() makes it.
Surface surface_of(const DoubleArray& control, const ScatteredSpec& s) {
  if (control.ndim() != 3 || control.shape(2) != 3)
    usage_error("control", "expected an (nu, nv, 3) array");
  Surface out;
  out.degree_u = s.degree_u;
  out.degree_v = s.degree_v;
  out.periodic_u = s.closed_u;
  out.periodic_v = s.closed_v;
  out.count_u = static_cast<int>(control.shape(0));
  out.count_v = static_cast<int>(control.shape(1));
  const std::size_t N = static_cast<std::size_t>(out.count_u) * out.count_v;
  out.control.resize(N);
  const double* c = control.data();
  for (std::size_t I = 0; I < N; ++I) out.control[I] = Point(c[3 * I], c[3 * I + 1], c[3 * I + 2]);
  return out;
}

long long cells_of(const ScatteredSpec& s, int nu, int nv) {
  const long long su = s.closed_u ? nu : nu - s.degree_u;
  const long long sv = s.closed_v ? nv : nv - s.degree_v;
  return su * sv;
}

py::object sheet_frame(py::handle mean, const DoubleArray& cov, py::handle along, py::handle first,
                       py::handle last) {
  if (cov.ndim() != 2 || cov.shape(0) != 3 || cov.shape(1) != 3)
    usage_error("cov", "expected a 3 x 3 array");
  Eigen::Matrix3d m;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) m(a, b) = cov.at(a, b);
  const auto f = detail::sheet_frame(point_from(mean, "mean"), m, point_from(along, "along"),
                                     point_from(first, "first"), point_from(last, "last"));
  if (!f) return py::none();
  const Point* p[3] = {&f->c, &f->along, &f->across};
  DoubleArray out({3, 3});
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out.mutable_at(a, b) = (*p[a])[b];
  return out;
}

DoubleArray sheet_positions(const DoubleArray& block, py::handle centre, const DoubleArray& frame) {
  const std::vector<Point> pts = centred_points(block, point_from(centre, "centre"));
  if (frame.ndim() != 2 || frame.shape(0) != 3 || frame.shape(1) != 3)
    usage_error("frame", "expected the 3 x 3 frame of _sheet_frame()");
  const detail::SheetFrame f{Point(frame.at(0, 0), frame.at(0, 1), frame.at(0, 2)),
                             Point(frame.at(1, 0), frame.at(1, 1), frame.at(1, 2)),
                             Point(frame.at(2, 0), frame.at(2, 1), frame.at(2, 2))};
  std::vector<double> u(pts.size()), v(pts.size());
  detail::sheet_positions(f, pts, u, v);
  DoubleArray out({static_cast<py::ssize_t>(pts.size()), py::ssize_t{2}});
  for (std::size_t k = 0; k < pts.size(); ++k) {
    out.mutable_data()[2 * k] = u[k];
    out.mutable_data()[2 * k + 1] = v[k];
  }
  return out;
}

// One chunk's data term, flat: band (nu nv x (2p+1)(2q+1)), then rhs (nu nv x 3, point-major).
DoubleArray partial(const DoubleArray& block, py::handle centre, const DoubleArray& fuv, int nu,
                    int nv, int degree_u, int degree_v, bool closed_u, bool closed_v) {
  const ScatteredSpec s = spec_of(degree_u, degree_v, closed_u, closed_v);
  const std::vector<Point> pts = centred_points(block, point_from(centre, "centre"));
  std::vector<double> fu, fv;
  fractions_of(fuv, pts.size(), fu, fv);
  const std::size_t N = static_cast<std::size_t>(nu) * nv,
                    W = static_cast<std::size_t>(2 * degree_u + 1) * (2 * degree_v + 1);
  std::vector<double> band(N * W, 0.0);
  std::vector<Point> rhs(N, Point::Zero());
  {
    py::gil_scoped_release nogil;
    detail::scattered_add(s, nu, nv, pts, {}, fu, fv, band, rhs);
  }
  DoubleArray out(static_cast<py::ssize_t>(N * (W + 3)));
  double* o = std::copy(band.begin(), band.end(), out.mutable_data());
  for (const Point& r : rhs) o = std::copy(r.data(), r.data() + 3, o);
  return out;
}

// The surface of the summed data term plus the smoothness term: control (nu, nv, 3) centred,
// or None where the factorisation failed.
py::object solve(const DoubleArray& flat, int nu, int nv, double smoothing, int degree_u,
                 int degree_v, bool closed_u, bool closed_v) {
  const ScatteredSpec s = spec_of(degree_u, degree_v, closed_u, closed_v);
  const std::size_t N = static_cast<std::size_t>(nu) * nv,
                    W = static_cast<std::size_t>(2 * degree_u + 1) * (2 * degree_v + 1);
  if (flat.ndim() != 1 || static_cast<std::size_t>(flat.shape(0)) != N * (W + 3))
    usage_error("partial", "normal equations of the wrong size for these counts");
  std::vector<double> band(flat.data(), flat.data() + N * W);
  std::vector<Point> rhs(N);
  for (std::size_t I = 0; I < N; ++I) {
    const double* r = flat.data() + N * W + 3 * I;
    rhs[I] = Point(r[0], r[1], r[2]);
  }
  Surface out;
  bool ok = false;
  {
    py::gil_scoped_release nogil;
    ok = detail::scattered_solve(s, nu, nv, band, rhs, smoothing, out);
  }
  if (!ok) return py::none();
  return points_to_array(out.control.data(), out.control.size()).reshape({nu, nv, 3});
}

// One chunk's check: [not within (0/1), not near (0/1), worst |S - D|_a / T_a, max |S - D| per
// axis (3), then each knot span's 1 where a point of the chunk lies in it], as the in-memory
// fit's judge (within T per axis, inside the ellipsoid of semi-axes T; round-off only on an
// axis whose T is 0) and covered_spans().
DoubleArray check(const DoubleArray& block, py::handle centre, const DoubleArray& fuv,
                  const DoubleArray& control, int degree_u, int degree_v, bool closed_u,
                  bool closed_v, py::handle tol, double roundoff) {
  const ScatteredSpec s = spec_of(degree_u, degree_v, closed_u, closed_v);
  const std::vector<Point> pts = centred_points(block, point_from(centre, "centre"));
  std::vector<double> fu, fv;
  fractions_of(fuv, pts.size(), fu, fv);
  const Surface surface = surface_of(control, s);
  const Point T = point_from(tol, "tol");
  const int nu = surface.count_u, nv = surface.count_v;
  const long long n_cells = cells_of(s, nu, nv);
  DoubleArray out(static_cast<py::ssize_t>(6 + n_cells));
  double* o = out.mutable_data();
  std::fill(o, o + 6 + n_cells, 0.0);
  {
    py::gil_scoped_release nogil;
    std::vector<double> u(pts.size()), v(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) {
      u[k] = fu[k] * domain_end(s.degree_u, nu, s.closed_u);
      v[k] = fv[k] * domain_end(s.degree_v, nv, s.closed_v);
    }
    Point semi;
    for (int a = 0; a < 3; ++a) semi[a] = T[a] + (T[a] == 0 ? roundoff : 0.0);
    const Point inverse = semi.array().inverse().matrix();
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const Point d = surface.evaluate(u[k], v[k]) - pts[k];
      const Point ad = d.cwiseAbs();
      if (!ad.allFinite()) {
        o[0] = o[1] = 1;
        o[2] = HUGE_VAL;
        continue;
      }
      for (int a = 0; a < 3; ++a) {
        if (ad[a] > semi[a]) o[0] = 1;
        o[2] = std::max(o[2], T[a] > 0 ? ad[a] / T[a] : (ad[a] > roundoff ? ad[a] / roundoff : 0));
        o[3 + a] = std::max(o[3 + a], ad[a]);
      }
      if (!(d.cwiseProduct(inverse).squaredNorm() <= 1)) o[1] = 1;
    }
    const std::vector<char> cells = detail::covered_spans(surface, u, v);
    for (long long c = 0; c < n_cells; ++c) o[6 + c] = cells[static_cast<std::size_t>(c)];
  }
  return out;
}

// The client's guards on a surface whose points held: (stays near the data's box where
// covered and calm elsewhere, as stays_near_where_covered(); the fold, and whether it folds).
py::tuple guards(const DoubleArray& control, const DoubleArray& cells, int degree_u, int degree_v,
                 bool closed_u, bool closed_v, py::handle box_min, py::handle box_max) {
  const ScatteredSpec s = spec_of(degree_u, degree_v, closed_u, closed_v);
  const Surface surface = surface_of(control, s);
  const Point lo = point_from(box_min, "box_min"), hi = point_from(box_max, "box_max");
  const Point centre = 0.5 * (lo + hi);
  const BoundingBox box{lo - centre, hi - centre};
  const int su = s.closed_u ? surface.count_u : surface.count_u - s.degree_u;
  const int sv = s.closed_v ? surface.count_v : surface.count_v - s.degree_v;
  if (cells.ndim() != 1 || cells.shape(0) != static_cast<py::ssize_t>(su) * sv)
    usage_error("cells", "one number per knot span expected");
  // One parameter pair inside each covered span: covered_spans() of these gives the cells.
  std::vector<double> u, v;
  for (int a = 0; a < su; ++a)
    for (int b = 0; b < sv; ++b)
      if (cells.at(static_cast<py::ssize_t>(a) * sv + b) != 0) {
        u.push_back(a + 0.5);
        v.push_back(b + 0.5);
      }
  const bool near = detail::stays_near_where_covered(surface, u, v, box);
  const double fold = detail::geometric_fold(surface);
  return py::make_tuple(near, fold, fold > kFoldRelative * (hi - lo).norm());
}

// One chunk's fractions moved to the closest points of the surface (project_parameters(),
// kNewtonSteps steps, then to_fractions()): the next round's parameters.
DoubleArray project(const DoubleArray& block, py::handle centre, const DoubleArray& fuv,
                    const DoubleArray& control, int degree_u, int degree_v, bool closed_u,
                    bool closed_v) {
  const ScatteredSpec s = spec_of(degree_u, degree_v, closed_u, closed_v);
  const std::vector<Point> pts = centred_points(block, point_from(centre, "centre"));
  std::vector<double> fu, fv;
  fractions_of(fuv, pts.size(), fu, fv);
  const Surface surface = surface_of(control, s);
  std::vector<double> nfu, nfv;
  {
    py::gil_scoped_release nogil;
    Rows rows;
    for (const Point& p : pts) rows.push_point(p);
    rows.end_row();
    const double eu = domain_end(s.degree_u, surface.count_u, s.closed_u),
                 ev = domain_end(s.degree_v, surface.count_v, s.closed_v);
    std::vector<double> u(pts.size()), v(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) {
      u[k] = fu[k] * eu;
      v[k] = fv[k] * ev;
    }
    detail::project_parameters(surface, rows, u, v, detail::kNewtonSteps, 1);
    detail::to_fractions(surface, u, v, nfu, nfv);
  }
  DoubleArray out({static_cast<py::ssize_t>(pts.size()), py::ssize_t{2}});
  for (std::size_t k = 0; k < pts.size(); ++k) {
    out.mutable_data()[2 * k] = nfu[k];
    out.mutable_data()[2 * k + 1] = nfv[k];
  }
  return out;
}

}  // namespace

void bind_geometric(py::module_& m) {
  m.def("_sheet_frame", &sheet_frame, py::arg("mean"), py::arg("cov"), py::arg("along"),
        py::arg("first"), py::arg("last"),
        "The base plane (3 x 3: mean, along, across) of gathered statistics, or None.");
  m.def("_sheet_positions", &sheet_positions, py::arg("block"), py::arg("centre"), py::arg("frame"),
        "Each point's (m, 2) position along and across the base plane.");
  m.def("_geometric_partial", &partial, py::arg("block"), py::arg("centre"), py::arg("fuv"),
        py::arg("nu"), py::arg("nv"), py::arg("degree_u"), py::arg("degree_v"), py::arg("closed_u"),
        py::arg("closed_v"), "One chunk's scattered data term, flat.");
  m.def("_geometric_partial_size", [](int nu, int nv, int degree_u, int degree_v) {
    return static_cast<long long>(nu) * nv * ((2 * degree_u + 1) * (2 * degree_v + 1) + 3);
  });
  m.def("_geometric_solve", &solve, py::arg("flat"), py::arg("nu"), py::arg("nv"),
        py::arg("smoothing"), py::arg("degree_u"), py::arg("degree_v"), py::arg("closed_u"),
        py::arg("closed_v"), "Control points (centred) of the summed data term, or None.");
  m.def(
      "_geometric_rules",
      [] {
        py::dict d;
        d["smoothing"] = detail::kSmoothing;
        d["smoothing_lower"] = detail::kSmoothingLower;
        d["smoothing_reach"] = detail::kSmoothingReach;
        d["correction_rounds"] = detail::kCorrectionRounds;
        d["max_unknowns"] = detail::kGeometricMaxUnknowns;
        return d;
      },
      "The geometric rule's constants (geometric_search.h, scattered_lsq.h).");
  m.def("_geometric_check", &check, py::arg("block"), py::arg("centre"), py::arg("fuv"),
        py::arg("control"), py::arg("degree_u"), py::arg("degree_v"), py::arg("closed_u"),
        py::arg("closed_v"), py::arg("tol"), py::arg("roundoff"),
        "One chunk's check and covered knot spans, flat (max-reduced).");
  m.def("_geometric_guards", &guards, py::arg("control"), py::arg("cells"), py::arg("degree_u"),
        py::arg("degree_v"), py::arg("closed_u"), py::arg("closed_v"), py::arg("box_min"),
        py::arg("box_max"), "(stays near, fold, folds) of a surface.");
  m.def("_geometric_project", &project, py::arg("block"), py::arg("centre"), py::arg("fuv"),
        py::arg("control"), py::arg("degree_u"), py::arg("degree_v"), py::arg("closed_u"),
        py::arg("closed_v"), "One chunk's fractions after a round of correction.");
}

}  // namespace sfit::python
