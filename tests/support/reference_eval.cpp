#include "reference_eval.h"

#include <nlohmann/json.hpp>

namespace sfit::test {

double cox_de_boor(const std::vector<double>& k, int i, int p, double t, double end) {
  // The recursion N_{i,p} = w N_{i,p-1} + (1 - w') N_{i+1,p-1}, evaluated bottom-up over the
  // p+1 degree-0 functions it needs (a table, so degree 20 costs 20^2, not 2^20), 0/0 = 0.
  std::vector<double> N(static_cast<std::size_t>(p + 1));
  for (int a = 0; a <= p; ++a) {
    const int m = i + a;
    const bool in = k[m] <= t && t < k[m + 1];
    // Close the domain on the right: the last non-empty span contains its end.
    const bool at_end = t == end && k[m] < k[m + 1] && k[m + 1] == end;
    N[a] = (in || at_end) ? 1.0 : 0.0;
  }
  for (int d = 1; d <= p; ++d)
    for (int a = 0; a + d <= p; ++a) {
      const int m = i + a;
      double v = 0;
      const double d1 = k[m + d] - k[m], d2 = k[m + d + 1] - k[m + 1];
      if (d1 > 0) v += (t - k[m]) / d1 * N[a];
      if (d2 > 0) v += (k[m + d + 1] - t) / d2 * N[a + 1];
      N[a] = v;
    }
  return N[0];
}

std::array<double, 3> ReferenceSurface::evaluate(double u, double v) const {
  std::array<double, 3> s{0, 0, 0};
  const int nu = static_cast<int>(cps.size()), nv = static_cast<int>(cps[0].size());
  for (int i = 0; i < nu; ++i) {
    const double bu = cox_de_boor(ku, i, p, u, u_end());
    if (bu == 0) continue;
    for (int j = 0; j < nv; ++j) {
      const double bv = cox_de_boor(kv, j, q, v, v_end());
      if (bv == 0) continue;
      for (int a = 0; a < 3; ++a) s[a] += bu * bv * cps[i][j][a];
    }
  }
  return s;
}

ReferenceSurface reference_from_json_text(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  ReferenceSurface r;
  r.p = j.at("degree")[0];
  r.q = j.at("degree")[1];
  r.ku = j.at("knots_u").get<std::vector<double>>();
  r.kv = j.at("knots_v").get<std::vector<double>>();
  for (const auto& row : j.at("control_points")) {
    std::vector<std::array<double, 3>> out;
    for (const auto& c : row)
      out.push_back({c[0].get<double>(), c[1].get<double>(), c[2].get<double>()});
    r.cps.push_back(std::move(out));
  }
  return r;
}

}  // namespace sfit::test
