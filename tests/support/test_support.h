// Helpers for the tests: data-set paths, sampled surfaces, running the CLI.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::test {

/// Uniform numbers from the raw generator (its output is fixed by the standard; the
/// distributions' are not), so generated test data is the same everywhere.
struct Uniform {
  std::mt19937 rng;
  explicit Uniform(std::uint32_t seed) : rng(seed) {}
  /// In [0, 1).
  double operator()() { return (static_cast<double>(rng()) + 0.5) / 4294967296.0; }
  /// In [a, b).
  double operator()(double a, double b) {
    return a + (b - a) * (static_cast<double>(rng()) + 0.5) / 4294967296.0;
  }
};

/// A fit's control points, nu x nv.
inline long size_of(const FitResult& f) {
  return static_cast<long>(f.surface.count_u) * f.surface.count_v;
}

/// The default options at T = `relative` of the bounding box's diagonal on every axis.
inline FitOptions at(const Rows& rows, double relative) {
  FitOptions o;
  o.tolerance = relative_tolerance(rows, relative);
  return o;
}

/// Path of a file in examples/.
std::string example(const std::string& name);
/// Path of a data set in examples/ (the README's "Data" table). The names of the models the
/// generated sets stand in for are accepted too (teapot_body.rows is ring_body.rows,
/// teapot_handle.rows bent_tube.rows, teapot_spout_small.rows spout_tube.rows, volcano.rows
/// height_field.rows, volcano_small.rows height_field_small.rows). Never "": every data set a
/// test uses is in the repository.
std::string shared_data(const std::string& name);
/// Reads a .rows file.
Rows load_rows(const std::string& path);

/// Rows sampled from f(s, t) with s in [0,1] along a row and t in [0,1] across rows:
/// counts[j] points in row j at s = k / (counts[j] - 1) (closed_u: k / counts[j]), and
/// t = j / (M - 1) (closed_v: j / M).
Rows sample_rows(const std::function<Point(double, double)>& f, const std::vector<int>& counts,
                 bool closed_u = false, bool closed_v = false);

/// Result of running the sfit executable.
struct Run {
  int exit_code = -1;
  std::string out, err;
};
/// Runs the CLI with `args` (shell-quoted here), optional stdin text.
Run run_cli(const std::string& args, const std::string& stdin_text = "");
/// `s` in single quotes, for run_cli() (paths without a quote of their own).
std::string shell_quoted(const std::string& s);
/// tests/bad_input/good.rows: a small valid input.
std::string good_rows();
/// A fresh empty temporary folder for this test.
std::string temp_dir();
std::string read_file(const std::string& path);
void write_file(const std::string& path, const std::string& text);

/// Largest per-axis deviation of every `stride`-th point from the fit at its assigned (u, v),
/// by the independent textbook evaluator (reference_eval.h) on the JSON contract form.
Point reference_deviation(const FitResult& fit, const Rows& rows, int stride = 1);
/// Expects (GoogleTest) the same surface bit for bit: counts, control points, u and v.
void expect_same_surface(const FitResult& a, const FitResult& b);

}  // namespace sfit::test
