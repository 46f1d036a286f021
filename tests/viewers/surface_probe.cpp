// sfit's own evaluation of a surface file, for the viewer tests (tests/viewers/*.py): the
// surface's counts, flags and domain, and S(u, v) on an n x n grid uniform in each parameter
// (a periodic direction without its repeated end), as JSON on standard output.
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
    std::printf("{\"degree\": [%d, %d], \"periodic\": [%s, %s], \"count\": [%d, %d],\n", s.degree_u,
                s.degree_v, s.periodic_u ? "true" : "false", s.periodic_v ? "true" : "false",
                s.count_u, s.count_v);
    std::printf(" \"domain\": [%.17g, %.17g], \"grid\": [\n", s.u_end(), s.v_end());
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a) {
        const double u = s.u_end() * a / (s.periodic_u ? n : n - 1);
        const double v = s.v_end() * b / (s.periodic_v ? n : n - 1);
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
