// sfit's own evaluation of a surface file, for the viewer tests (tests/viewers/*.py): the
// surface's counts, flags and domain, and S(u, v) on an n x n grid uniform in each parameter
// (a closed direction without its repeated end), as JSON on standard output. A direction is
// closed ("periodic" in the JSON printed, as a mesh wraps it) where the surface is periodic, or
// clamped with its first and last control-point columns (rows) equal: closed corner knots.
//   surface_probe SURFACE.json [n]
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "sfit/error.h"
#include "sfit/io/surface_json.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: surface_probe SURFACE.json [n]\n");
    return 2;
  }
  try {
    const sfit::Surface s = sfit::io::read_surface_json(argv[1]);
    const int n = argc > 2 ? std::atoi(argv[2]) : 11;
    auto ends_equal = [&](bool along_v) {
      const int nu = s.count_u, nv = s.count_v;
      for (int k = 0; k < (along_v ? nu : nv); ++k)
        if (along_v ? s.control[k * nv] != s.control[k * nv + nv - 1]
                    : s.control[k] != s.control[(nu - 1) * nv + k])
          return false;
      return true;
    };
    const bool cu = s.periodic_u || ends_equal(false), cv = s.periodic_v || ends_equal(true);
    std::printf("{\"degree\": [%d, %d], \"periodic\": [%s, %s], \"count\": [%d, %d],\n", s.degree_u,
                s.degree_v, cu ? "true" : "false", cv ? "true" : "false", s.count_u, s.count_v);
    std::printf(" \"domain\": [%.17g, %.17g], \"grid\": [\n", s.u_end(), s.v_end());
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a) {
        const double u = s.u_end() * a / (cu ? n : n - 1);
        const double v = s.v_end() * b / (cv ? n : n - 1);
        const sfit::Point p = s.evaluate(u, v);
        std::printf("  [%.17g, %.17g, %.17g, %.17g, %.17g]%s\n", u, v, p.x(), p.y(), p.z(),
                    a == n - 1 && b == n - 1 ? "" : ",");
      }
    std::printf("]}\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "surface_probe: %s\n", e.what());
    return 1;
  }
  return 0;
}
