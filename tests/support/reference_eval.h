// An independent evaluator for the tests: the plain Cox-de Boor recursion on the full knot
// vectors of the docs/surface-json.md form, sharing no code with sfit's basis.cpp.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace sfit::test {

/// N_{i,p}(t) by the textbook recursion (0/0 = 0); the right end of the domain is included
/// in the last non-empty span.
double cox_de_boor(const std::vector<double>& knots, int i, int p, double t, double domain_end);

struct ReferenceSurface {
  int p = 0, q = 0;
  std::vector<double> ku, kv;
  std::vector<std::vector<std::array<double, 3>>> cps;  // [i][j] full arrays
  std::array<double, 3> evaluate(double u, double v) const;
  double u_begin() const { return ku[p]; }
  double u_end() const { return ku[cps.size()]; }
  double v_begin() const { return kv[q]; }
  double v_end() const { return kv[cps[0].size()]; }
};

/// Parses the JSON text of a surface file (needs only the contract's keys).
ReferenceSurface reference_from_json_text(const std::string& text);

}  // namespace sfit::test
