// The library in a dozen lines: read rows, fit within 1e-3 of the diagonal, print the report.
#include <cstdio>

#include "sfit/error.h"
#include "sfit/io/rows_reader.h"
#include "sfit/surface_fit.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fit_example INPUT.rows\n");
    return 2;
  }
  try {
    const sfit::Rows rows = sfit::io::read_rows(argv[1]).rows;
    sfit::FitOptions options;  // bicubic, open/open
    options.tolerance = sfit::relative_tolerance(rows, 1e-3);
    const sfit::FitResult fit = sfit::fit_surface(rows, options);
    const auto& r = fit.report;
    std::printf("%zu rows, %zu points -> %d x %d control points\n", r.rows, r.points, r.count_u,
                r.count_v);
    std::printf("max deviation (%.3g, %.3g, %.3g), tolerance %.3g\n", r.max_deviation.x(),
                r.max_deviation.y(), r.max_deviation.z(), r.tolerance.x());
    std::printf("within tolerance: %s\n", r.within_tolerance ? "yes" : "no");
    std::printf("S(0,0) = (%.6g, %.6g, %.6g)\n", fit.surface.evaluate(0, 0).x(),
                fit.surface.evaluate(0, 0).y(), fit.surface.evaluate(0, 0).z());
    return r.within_tolerance ? 0 : 7;
  } catch (const sfit::Error& e) {
    std::fprintf(stderr, "fit_example: %s\n", e.what());
    return e.exit_code();
  }
}
