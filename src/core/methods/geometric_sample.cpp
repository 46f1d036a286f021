// The geometric search's sample of large data (geometric_sample.h).
#include "geometric_sample.h"

#include <algorithm>
#include <cmath>

namespace sfit::detail {

Sample take_sample(const Rows& rows, std::size_t step) {
  Sample s;
  const auto& off = rows.offsets();
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const auto row = rows[j];
    for (std::size_t k = 0; k < row.size(); ++k) {
      if (k % step != 0 && k + 1 != row.size()) continue;
      s.rows.push_point(row[k]);
      s.index.push_back(off[j] + k);
      if (rows.weighted()) s.rows.push_weight(rows.weights()[off[j] + k]);
    }
    s.rows.end_row();
  }
  return s;
}

void carry_sample_corrections(const Rows& rows, const std::vector<std::size_t>& index,
                              const std::vector<double>& fu, const std::vector<double>& fv,
                              const std::vector<double>& fu0, const std::vector<double>& fv0,
                              bool closed_u, std::vector<double>& full_u,
                              std::vector<double>& full_v) {
  const auto& off = rows.offsets();
  std::size_t s0 = 0;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const std::size_t begin = s0;
    while (s0 < index.size() && index[s0] < off[j + 1]) ++s0;
    for (std::size_t s = begin; s < s0; ++s) {
      const std::size_t k0 = index[s];
      const double du0 = fu[s] - fu0[s], dv0 = fv[s] - fv0[s];
      const bool has_next = s + 1 < s0;
      const std::size_t k1 = has_next ? index[s + 1] : k0 + 1;
      const double du1 = has_next ? fu[s + 1] - fu0[s + 1] : du0,
                   dv1 = has_next ? fv[s + 1] - fv0[s + 1] : dv0;
      for (std::size_t k = k0; k < k1 && k < off[j + 1]; ++k) {
        const double t = static_cast<double>(k - k0) / static_cast<double>(k1 - k0);
        double u = full_u[k] + (1 - t) * du0 + t * du1;
        if (closed_u) {
          u -= std::floor(u);
          if (u >= 1) u = 0;
        } else {
          u = std::clamp(u, 0.0, 1.0);
        }
        full_u[k] = u;
        full_v[k] = std::clamp(full_v[k] + (1 - t) * dv0 + t * dv1, 0.0, 1.0);
      }
    }
  }
}

}  // namespace sfit::detail
