// The uniform and the adaptive-knot fits of one data set, and the checks both adaptive-knot
// tests make (adaptive_knots_test.cpp, adaptive_knots_closed_test.cpp).
#pragma once

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::test {

struct UniformAndAdaptive {
  FitResult uniform, adaptive;
};

/// The default fit at T = `fraction` of the diagonal on uniform knots alone (KnotRule::kUniform),
/// then with KnotRule::kAdaptive (rows closed when `closed_u`).
UniformAndAdaptive fit_both(const Rows& rows, double fraction, bool closed_u = false);

/// nu x nv.
long count(const FitResult& r);

/// Prints the two counts and their ratio ("[ measure  ] name T ...: uniform ..., adaptive ...").
void report(const char* name, double fraction, const UniformAndAdaptive& p);

/// The adaptive fit is the uniform one, bit for bit (control points, uniform knots, the
/// report's knot rule).
void expect_uniform_kept(const UniformAndAdaptive& p);

/// T at every point by the textbook evaluation of the surface's JSON at the point's (u, v),
/// the report's within_tolerance, and no fold across the rows.
void expect_holds_at_parameters(const Rows& rows, const FitResult& r);

}  // namespace sfit::test
