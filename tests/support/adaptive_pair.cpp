// The uniform and the adaptive-knot fits, and their checks (adaptive_pair.h).
#include "adaptive_pair.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "reference_eval.h"
#include "sfit/fold_check.h"
#include "sfit/io/surface_json.h"

namespace sfit::test {

UniformAndAdaptive fit_both(const Rows& rows, double fraction, bool closed_u) {
  FitOptions o;
  o.closed_u = closed_u;
  o.tolerance = relative_tolerance(rows, fraction);
  UniformAndAdaptive p;
  o.knots = KnotRule::kUniform;
  p.uniform = fit_surface(rows, o);
  o.knots = KnotRule::kAdaptive;
  p.adaptive = fit_surface(rows, o);
  return p;
}

long count(const FitResult& r) {
  return static_cast<long>(r.surface.count_u) * r.surface.count_v;
}

void report(const char* name, double fraction, const UniformAndAdaptive& p) {
  std::printf("[ measure  ] %-20s T %.0e: uniform %d x %d = %ld, adaptive %d x %d = %ld (%.2f)\n",
              name, fraction, p.uniform.surface.count_u, p.uniform.surface.count_v,
              count(p.uniform), p.adaptive.surface.count_u, p.adaptive.surface.count_v,
              count(p.adaptive), double(count(p.adaptive)) / count(p.uniform));
}

void expect_uniform_kept(const UniformAndAdaptive& p) {
  EXPECT_EQ(p.adaptive.surface.control, p.uniform.surface.control);
  EXPECT_FALSE(p.adaptive.surface.non_uniform());
  EXPECT_EQ(p.adaptive.report.knots, KnotRule::kUniform);
}

void expect_holds_at_parameters(const Rows& rows, const FitResult& r) {
  const ReferenceSurface ref = reference_from_json_text(io::surface_to_json_text(r.surface));
  const Point tol = r.report.tolerance;
  std::size_t k = 0, missed = 0;
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (const Point& d : rows[j]) {
      const auto e = ref.evaluate(r.u[k], r.point_v(j, k));
      ++k;
      for (int a = 0; a < 3; ++a)
        if (std::abs(e[a] - d[a]) > tol[a] * (1 + 1e-9)) ++missed;
    }
  EXPECT_EQ(missed, 0u);
  EXPECT_TRUE(r.report.within_tolerance);
  EXPECT_LE(fold_measure(r.surface, r.v), kFoldRelative * bounding_box(rows).diagonal());
}

}  // namespace sfit::test
