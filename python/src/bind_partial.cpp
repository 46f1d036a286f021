// The pieces of the distributed fit (python/sfit/dask.py, docs/python.md "More than one
// machine"): what a worker computes from one chunk of points, what the client solves, and the
// in-memory fit at given counts the distributed one is compared with. Private (underscore
// names); plain numpy arrays in and out, so every task result pickles.
//
// A chunk is an (m, 4) array of centred-or-not points (x, y, z, row) whose rows are numbered
// 0 ... M-1 and stored consecutively in row order across the whole data set; `g0` is the
// chunk's first point's position in the data set, `first_row` the row of its first point, and
// `starts`/`sizes` give, for rows first_row ... of the chunk, the position of their first
// point and their number of points (the per-row statistics the client gathered first). So a
// row may span chunks: each point knows its index in its row, and its parameter is the one the
// in-memory fit gives it.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "basis.h"
#include "bindings.h"
#include "convert.h"
#include "errors.h"
#include "fit_frame.h"
#include "normal_equations.h"
#include "parameters.h"

namespace sfit::python {
namespace {

using detail::NormalEquations;
using detail::TensorSpec;
using LongArray = py::array_t<long long, py::array::c_style | py::array::forcecast>;

Parametrization rule_of(const std::string& name) {
  Parametrization r;
  if (!parse_parametrization(name, r) ||
      (r != Parametrization::kUniform && r != Parametrization::kPaper))
    usage_error("parameters", "'" + name + "' is not one of uniform, paper (distributed fit)");
  return r;
}

TensorSpec spec_of(int degree_u, int degree_v, bool closed_u, bool closed_v,
                   const std::string& rule) {
  TensorSpec s;
  s.degree_u = degree_u;
  s.degree_v = degree_v;
  s.closed_u = closed_u;
  s.closed_v = closed_v;
  s.rule = rule_of(rule);
  return s;
}

// One chunk read in place (no copy of its points): the (m, 4) block, the centre subtracted
// on the fly, and its runs of points of one row, each with the row, the index of its first
// point in the row and the row's size.
struct Run {
  std::size_t a, b;  // the run's points [a, b) in the chunk
  long long row, k0, size;
};

struct Chunk {
  const double* data;  // row-major (m, 4)
  Point centre;
  std::vector<Run> runs;
  Point point(std::size_t k) const {
    const double* q = data + 4 * k;
    return Point(q[0] - centre[0], q[1] - centre[1], q[2] - centre[2]);
  }
};

// The runs of one block; call without the GIL (the arrays are held by the caller).
Chunk chunk_from(const DoubleArray& block, long long g0, long long first_row,
                 const LongArray& starts, const LongArray& sizes, const Point& centre) {
  if (block.ndim() != 2 || block.shape(1) != 4)
    usage_error("points", "a chunk must be an (m, 4) array (x, y, z, row)");
  const std::size_t m = static_cast<std::size_t>(block.shape(0));
  const long long rows_known = starts.shape(0);
  if (sizes.shape(0) != rows_known) usage_error("points", "starts and sizes differ in length");
  const long long* st = starts.data();
  const long long* sz = sizes.data();
  Chunk c{block.data(), centre, {}};
  std::size_t a = 0;
  while (a < m) {
    const double ra = c.data[4 * a + 3];
    std::size_t b = a + 1;
    while (b < m && c.data[4 * b + 3] == ra) ++b;
    const long long r = static_cast<long long>(ra);
    const long long j = r - first_row;
    if (static_cast<double>(r) != ra || j < 0 || j >= rows_known)
      usage_error("points", "chunk point " + std::to_string(a) + ": row " + std::to_string(ra) +
                                " out of the rows counted");
    const long long k0 = g0 + static_cast<long long>(a) - st[j];
    if (k0 < 0 || k0 + static_cast<long long>(b - a) > sz[j])
      usage_error("points",
                  "rows must be stored consecutively in row order (row " + std::to_string(r) + ")");
    c.runs.push_back(Run{a, b, r, k0, sz[j]});
    a = b;
  }
  return c;
}

// v of every row at nv, as TensorProblem::v_at() gives it for the rule.
std::vector<double> v_of(const TensorSpec& s, int nv, long long rows) {
  const int M = static_cast<int>(rows);
  if (s.rule == Parametrization::kPaper) return paper_parameters(s.degree_v, nv, s.closed_v, M);
  const std::vector<Point> column(static_cast<std::size_t>(M));
  return scaled_parameters(s.degree_v, nv, s.closed_v,
                           normalized_positions(column, Parametrization::kUniform, s.closed_v));
}

// u of the points [a, b) of one row segment of the chunk at nu, as TensorProblem's moments().
std::vector<double> u_of(const TensorSpec& s, int nu, const Run& run) {
  const std::size_t a = run.a, b = run.b;
  const int n = static_cast<int>(run.size);
  const long long k0 = run.k0;
  std::vector<double> t(b - a);
  if (s.rule == Parametrization::kPaper) {
    const std::vector<double> all = paper_parameters(s.degree_u, nu, s.closed_u, n);
    std::copy(all.begin() + k0, all.begin() + k0 + static_cast<long long>(b - a), t.begin());
    return t;
  }
  // normalized_positions() at the uniform rule, for these indices only.
  std::vector<double> f(b - a, 0.0);
  if (n >= 2) {
    const double steps = s.closed_u ? n : n - 1;
    for (std::size_t k = 0; k < f.size(); ++k) f[k] = static_cast<double>(k0 + k) / steps;
    if (!s.closed_u && k0 + static_cast<long long>(f.size()) == n) f.back() = 1.0;
  }
  return scaled_parameters(s.degree_u, nu, s.closed_u, f);
}

Point point3(py::handle h, const char* what) {
  return point_from(h, what);
}

// The flat layout of a chunk's normal equations: st, rhs (column-major n x 3), gbar, hs, s_sum.
std::size_t flat_size(const NormalEquations& ne) {
  return ne.st.size() + static_cast<std::size_t>(ne.rhs.size()) + ne.gbar.size() + ne.hs.size() + 1;
}

DoubleArray partial(const DoubleArray& block, long long g0, long long first_row,
                    const LongArray& starts, const LongArray& sizes, long long rows,
                    py::handle centre, int nu, int nv, int degree_u, int degree_v, bool closed_u,
                    bool closed_v, const std::string& rule) {
  const TensorSpec s = spec_of(degree_u, degree_v, closed_u, closed_v, rule);
  const Point mid = point3(centre, "centre");
  DoubleArray out;
  {
    py::gil_scoped_release nogil;
    const Chunk c = chunk_from(block, g0, first_row, starts, sizes, mid);
    NormalEquations ne(s, nu, nv, true);
    const std::vector<double> v = v_of(s, nv, rows);
    const int p = s.degree_u, w = p + 1;
    std::vector<double> G(static_cast<std::size_t>(nu) * w);
    std::vector<Point> R(static_cast<std::size_t>(nu));
    std::array<double, kMaxDegree + 1> bu;
    for (const Run& run : c.runs) {
      const std::vector<double> t = u_of(s, nu, run);
      std::fill(G.begin(), G.end(), 0.0);
      std::fill(R.begin(), R.end(), Point::Zero());
      for (std::size_t k = run.a; k < run.b; ++k) {  // as TensorProblem's moments()
        const Point d = c.point(k);
        const int f = eval_basis(p, nu, s.closed_u, t[k - run.a], bu.data());
        for (int i = 0; i < w; ++i) {
          const int q = wrap_index(f + i, nu);
          R[q] += (1.0 * bu[i]) * d;
          for (int e = 0; i + e < w; ++e) G[q * w + e] += bu[i] * bu[i + e];
        }
      }
      ne.add_row(G.data(), R.data(), v[run.row]);
    }
    py::gil_scoped_acquire gil;
    out = DoubleArray(static_cast<py::ssize_t>(flat_size(ne)));
    double* o = out.mutable_data();
    o = std::copy(ne.st.begin(), ne.st.end(), o);
    o = std::copy(ne.rhs.data(), ne.rhs.data() + ne.rhs.size(), o);
    o = std::copy(ne.gbar.begin(), ne.gbar.end(), o);
    o = std::copy(ne.hs.begin(), ne.hs.end(), o);
    *o = ne.s_sum;
  }
  return out;
}

long long partial_size(int nu, int nv, int degree_u, int degree_v) {
  const long long n = static_cast<long long>(nu) * nv;
  return n * (degree_u + 1) * (2 * degree_v + 1) + 3 * n +
         static_cast<long long>(nu) * (degree_u + 1) + static_cast<long long>(nv) * (degree_v + 1) +
         1;
}

// (holds, control points (nu, nv, 3) centred or None, the failed guard's name or None).
py::tuple solve_flat(const DoubleArray& flat, int nu, int nv, int degree_u, int degree_v,
                     bool closed_u, bool closed_v, long long min_points, py::handle box_min,
                     py::handle box_max) {
  const TensorSpec s = spec_of(degree_u, degree_v, closed_u, closed_v, "uniform");
  NormalEquations ne(s, nu, nv, true);
  if (flat.ndim() != 1 || static_cast<std::size_t>(flat.shape(0)) != flat_size(ne))
    usage_error("partial", "normal equations of the wrong size for these counts");
  const BoundingBox box{point3(box_min, "box_min"), point3(box_max, "box_max")};
  const Point centre = 0.5 * (box.min + box.max);
  Surface surface;
  bool ok = false;
  const char* guard = nullptr;
  {
    py::gil_scoped_release nogil;
    const double* p = flat.data();
    std::copy(p, p + ne.st.size(), ne.st.begin());
    p += ne.st.size();
    std::copy(p, p + ne.rhs.size(), ne.rhs.data());
    p += ne.rhs.size();
    std::copy(p, p + ne.gbar.size(), ne.gbar.begin());
    p += ne.gbar.size();
    std::copy(p, p + ne.hs.size(), ne.hs.begin());
    p += ne.hs.size();
    ne.s_sum = *p;
    const bool cg = detail::tries_cg(s, nu, nv, static_cast<int>(min_points));
    ok = detail::solve(ne, cg, surface);
    if (ok) guard = detail::failed_guard(surface, BoundingBox{box.min - centre, box.max - centre});
  }
  if (!ok) return py::make_tuple(false, py::none(), py::none());
  py::array_t<double> control({nu, nv, 3});
  auto m = control.mutable_unchecked<3>();
  for (int i = 0; i < nu; ++i)
    for (int l = 0; l < nv; ++l)
      for (int a = 0; a < 3; ++a) m(i, l, a) = surface.at(i, l)[a];
  return py::make_tuple(true, control, guard ? py::object(py::str(guard)) : py::object(py::none()));
}

Surface surface_of(const DoubleArray& control, int degree_u, int degree_v, bool closed_u,
                   bool closed_v, const Point& centre) {
  if (control.ndim() != 3 || control.shape(2) != 3)
    usage_error("control", "expected an (nu, nv, 3) array");
  Surface s;
  TensorSpec spec;
  spec.degree_u = degree_u;
  spec.degree_v = degree_v;
  spec.closed_u = closed_u;
  spec.closed_v = closed_v;
  const int nu = static_cast<int>(control.shape(0)), nv = static_cast<int>(control.shape(1));
  detail::shape(s, spec, nu, nv);
  const auto c = control.unchecked<3>();
  for (int i = 0; i < nu; ++i)
    for (int l = 0; l < nv; ++l) s.at(i, l) = Point(c(i, l, 0), c(i, l, 1), c(i, l, 2)) + centre;
  return s;
}

// Max |S(u, v) - D| per axis over the chunk, S the centred surface of `control`.
DoubleArray deviation(const DoubleArray& block, long long g0, long long first_row,
                      const LongArray& starts, const LongArray& sizes, long long rows,
                      py::handle centre, const DoubleArray& control, int degree_u, int degree_v,
                      bool closed_u, bool closed_v, const std::string& rule) {
  const TensorSpec s = spec_of(degree_u, degree_v, closed_u, closed_v, rule);
  const Point mid = point3(centre, "centre");
  const Surface surface =
      surface_of(control, degree_u, degree_v, closed_u, closed_v, Point::Zero());
  Point worst = Point::Zero();
  {
    py::gil_scoped_release nogil;
    const Chunk c = chunk_from(block, g0, first_row, starts, sizes, mid);
    const std::vector<double> v = v_of(s, surface.count_v, rows);
    // Surface::evaluate() with the v half made once per run (a run has one v): the same
    // arithmetic in the same order, so the same bits.
    const int pu = surface.degree_u, pv = surface.degree_v, nu = surface.count_u;
    std::vector<Point> curve(static_cast<std::size_t>(nu));
    std::array<double, kMaxDegree + 1> bu, bv;
    for (const Run& run : c.runs) {
      const int fv = eval_basis(pv, surface.count_v, surface.periodic_v, v[run.row], bv.data());
      for (int i = 0; i < nu; ++i) {
        Point row = Point::Zero();
        for (int b = 0; b <= pv; ++b)
          row += bv[b] * surface.at(i, wrap_index(fv + b, surface.count_v));
        curve[i] = row;
      }
      const std::vector<double> t = u_of(s, nu, run);
      for (std::size_t k = run.a; k < run.b; ++k) {
        const int fu = eval_basis(pu, nu, surface.periodic_u, t[k - run.a], bu.data());
        Point q = Point::Zero();
        for (int a = 0; a <= pu; ++a) q += bu[a] * curve[wrap_index(fu + a, nu)];
        worst = worst.cwiseMax((q - c.point(k)).cwiseAbs());
      }
    }
  }
  DoubleArray out(3);
  for (int a = 0; a < 3; ++a) out.mutable_at(a) = worst[a];
  return out;
}

}  // namespace

void bind_partial(py::module_& m) {
  m.def("_partial_normal_equations", &partial, py::arg("block"), py::arg("g0"),
        py::arg("first_row"), py::arg("starts"), py::arg("sizes"), py::arg("rows"),
        py::arg("centre"), py::arg("nu"), py::arg("nv"), py::arg("degree_u"), py::arg("degree_v"),
        py::arg("closed_u"), py::arg("closed_v"), py::arg("parameters"),
        "One chunk's normal equations at (nu, nv), flat (sfit.dask).");
  m.def("_partial_size", &partial_size, py::arg("nu"), py::arg("nv"), py::arg("degree_u"),
        py::arg("degree_v"), "Numbers in one chunk's normal equations.");
  m.def("_solve_normal_equations", &solve_flat, py::arg("flat"), py::arg("nu"), py::arg("nv"),
        py::arg("degree_u"), py::arg("degree_v"), py::arg("closed_u"), py::arg("closed_v"),
        py::arg("min_points"), py::arg("box_min"), py::arg("box_max"),
        "The surface of summed normal equations (centred): (solved, control, failed guard).");
  m.def("_chunk_deviation", &deviation, py::arg("block"), py::arg("g0"), py::arg("first_row"),
        py::arg("starts"), py::arg("sizes"), py::arg("rows"), py::arg("centre"), py::arg("control"),
        py::arg("degree_u"), py::arg("degree_v"), py::arg("closed_u"), py::arg("closed_v"),
        py::arg("parameters"), "Max |S - D| per axis over one chunk (control centred).");
  m.def(
      "_surface_from_control",
      [](const DoubleArray& control, int degree_u, int degree_v, bool closed_u, bool closed_v,
         py::handle centre) {
        return surface_of(control, degree_u, degree_v, closed_u, closed_v,
                          point3(centre, "centre"));
      },
      py::arg("control"), py::arg("degree_u"), py::arg("degree_v"), py::arg("closed_u"),
      py::arg("closed_v"), py::arg("centre"), "An sfit.Surface of centred control points.");
  m.def(
      "_row_parameters",
      [](long long rows, int nv, int degree_v, bool closed_v, const std::string& rule) {
        return vector_to_array(v_of(spec_of(3, degree_v, false, closed_v, rule), nv, rows));
      },
      py::arg("rows"), py::arg("nv"), py::arg("degree_v"), py::arg("closed_v"),
      py::arg("parameters"), "v of every row at nv, as the in-memory fit gives them.");
  m.def(
      "_fit_at_counts",
      [](py::handle rows, int nu, int nv, py::handle tol, int degree_u, int degree_v, bool closed_u,
         bool closed_v, const std::string& rule, int threads) {
        auto r = std::make_shared<Rows>(rows_from(rows));
        FitOptions o;
        o.degree_u = degree_u;
        o.degree_v = degree_v;
        o.closed_u = closed_u;
        o.closed_v = closed_v;
        o.tolerance = per_axis_from(tol, "tol");
        // Also the geometric rule (the library's fixed-count path: geometric_at_counts()).
        o.parametrization = rule == "geometric" ? Parametrization::kGeometric : rule_of(rule);
        o.counts = std::array<int, 2>{nu, nv};
        o.norm = FitNorm::kL2;
        o.seam = SeamMode::kKeep;
        o.orient = OrientMode::kKeep;
        o.threads = threads;
        FitResult result;
        {
          py::gil_scoped_release nogil;
          result = fit_surface(*r, o);
        }
        return py::cast(PyFit{std::move(result), std::move(r)});
      },
      py::arg("rows"), py::arg("nu"), py::arg("nv"), py::arg("tol"), py::arg("degree_u") = 3,
      py::arg("degree_v") = 3, py::arg("closed_u") = false, py::arg("closed_v") = false,
      py::arg("parameters") = "uniform", py::arg("threads") = 0,
      "The in-memory least-squares fit at exactly (nu, nv) (FitOptions::counts, least "
      "squares, one rule (uniform, paper or geometric), seams and orientation kept): what "
      "sfit.dask.fit() equals.");
}

}  // namespace sfit::python
