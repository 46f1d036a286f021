// Fits a 3 x 4 sheet with the installed library and prints the counts.
#include <cstdio>

#include "sfit/surface_fit.h"

int main() {
  sfit::Rows rows;
  for (int j = 0; j < 3; ++j) {
    for (int k = 0; k < 4; ++k) rows.push_point(sfit::Point(k, j, 0.1 * k * j));
    rows.end_row();
  }
  sfit::FitOptions o;
  o.degree_u = o.degree_v = 2;
  o.tolerance = sfit::Point::Constant(1e-6);
  const auto r = sfit::fit_surface(rows, o);
  std::printf("consumer: %d x %d, within tolerance: %s\n", r.surface.count_u, r.surface.count_v,
              r.report.within_tolerance ? "yes" : "no");
  return r.report.within_tolerance ? 0 : 1;
}
