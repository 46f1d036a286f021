#include "best_effort.h"

#include <algorithm>
#include <array>
#include <string>

#include "sfit/error.h"

namespace sfit::server {

std::unique_ptr<IncrementalFit> fit_or_best_effort(Rows rows, const FitOptions& options,
                                                   std::string& why) {
  why.clear();
  try {
    return std::make_unique<IncrementalFit>(rows, options);
  } catch (const Error& e) {
    if (e.code() != ErrorCode::kToleranceNotMet) throw;
    why = e.message();
  }
  FitOptions b = options;
  b.method = FitMethod::kSurface;
  if (b.search == CountSearch::kKnown) b.search = CountSearch::kFast;
  b.row_count_hints.clear();
  b.column_count_hints.clear();
  std::size_t longest = 0;
  for (std::size_t j = 0; j < rows.size(); ++j) longest = std::max(longest, rows[j].size());
  const int most_u = std::max(1, static_cast<int>(longest) - 1);
  const int most_v = std::max(1, static_cast<int>(rows.size()) - 1);
  // At the degrees asked for; where no pair solves there (a degree above what the rows can
  // take), at the degrees the data can take, then at most cubic: the report says which.
  const std::array<std::array<int, 2>, 3> degrees{{
      {options.degree_u, options.degree_v},
      {std::min(options.degree_u, most_u), std::min(options.degree_v, most_v)},
      {std::min({options.degree_u, most_u, 3}), std::min({options.degree_v, most_v, 3})},
  }};
  for (std::size_t k = 0; k < degrees.size(); ++k) {
    if (k > 0 && degrees[k] == degrees[k - 1]) continue;
    b.degree_u = degrees[k][0];
    b.degree_v = degrees[k][1];
    const int lo_u = b.degree_u + 1, lo_v = b.degree_v + 1;
    int nu = std::max(lo_u, static_cast<int>(longest));
    int nv = std::max(lo_v, static_cast<int>(rows.size()));
    // The most control points first (closest to interpolation), then fewer, until one solves.
    for (int tries = 0; tries < 64; ++tries) {
      b.counts = std::array<int, 2>{nu, nv};
      try {
        auto fit = std::make_unique<IncrementalFit>(rows, b);
        why += "; shown: the surface at " + std::to_string(nu) + " x " + std::to_string(nv) +
               " control points, degree " + std::to_string(b.degree_u) + " x " +
               std::to_string(b.degree_v);
        return fit;
      } catch (const Error& e) {
        if (e.code() != ErrorCode::kToleranceNotMet && e.code() != ErrorCode::kUsage) throw;
      }
      if (nu == lo_u && nv == lo_v) break;
      nu = std::max(lo_u, nu - std::max(1, nu / 4));
      nv = std::max(lo_v, nv - std::max(1, nv / 4));
    }
  }
  // Last, the search itself at those lower degrees (its two stages take fewer rows than the
  // fixed-count solve).
  FitOptions c = options;
  c.degree_u = degrees[2][0];
  c.degree_v = degrees[2][1];
  if (c.degree_u != options.degree_u || c.degree_v != options.degree_v) {
    try {
      auto fit = std::make_unique<IncrementalFit>(rows, c);
      why += "; shown: the fit at degree " + std::to_string(c.degree_u) + " x " +
             std::to_string(c.degree_v);
      return fit;
    } catch (const Error& e) {
      if (e.code() != ErrorCode::kToleranceNotMet) throw;
    }
  }
  throw Error(ErrorCode::kToleranceNotMet, why + "; and no surface at fixed counts solves either");
}

}  // namespace sfit::server
