// Test helper: evaluates a saved surface with the C++ library, for the Python tests.
// Usage: sfit_python_eval_helper SURFACE.json < "u v" lines; prints per line
// "x y z  Su(x y z)  Sv(x y z)" in %.17g (each value round-trips exactly).
#include <cstdio>

#include "sfit/error.h"
#include "sfit/io/surface_json.h"
#include "sfit/surface_eval.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SURFACE.json < uv.txt\n", argv[0]);
    return 2;
  }
  try {
    const sfit::Surface s = sfit::io::read_surface_json(argv[1]);
    double u = 0, v = 0;
    while (std::scanf("%lf %lf", &u, &v) == 2) {
      const sfit::Point p = s.evaluate(u, v);
      sfit::Point d[3];
      sfit::surface_derivatives(s, u, v, 1, d);  // the module's derivatives
      std::printf("%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", p.x(), p.y(), p.z(),
                  d[1].x(), d[1].y(), d[1].z(), d[2].x(), d[2].y(), d[2].z());
    }
  } catch (const sfit::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return e.exit_code();
  }
  return 0;
}
