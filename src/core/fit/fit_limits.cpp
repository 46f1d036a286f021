#include "sfit/fit_limits.h"

#include <cmath>
#include <cstdio>

#include "basis.h"
#include "sfit/error.h"

namespace sfit {

static_assert(kMaxFitDegree == kMaxDegree, "the fit's degree limit is the basis's");

namespace {
std::string g(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}
}  // namespace

void check_degree(int d, const std::string& option) {
  if (d < kMinFitDegree || d > kMaxFitDegree)
    throw Error(ErrorCode::kUsage,
                "degree " + std::to_string(d) + " is out of range " +
                    std::to_string(kMinFitDegree) + " ... " + std::to_string(kMaxFitDegree),
                Place{.option = option}, {static_cast<double>(d)});
}

void check_threads(int t, const std::string& option) {
  if (t < 0 || t > kMaxThreads)
    throw Error(
        ErrorCode::kUsage,
        std::to_string(t) + " threads: give 0 (all cores) ... " + std::to_string(kMaxThreads),
        Place{.option = option}, {static_cast<double>(t)});
}

void check_tolerance_fraction(double f, const std::string& option) {
  if (!(f >= 0 && f <= 1))
    throw Error(ErrorCode::kUsage,
                "must be a fraction 0 ... 1 of the bounding-box diagonal, got " + g(f),
                Place{.option = option}, {f});
}

void check_tolerance(const Point& t, const std::string& option) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(t[k]) || t[k] < 0)
      throw Error(ErrorCode::kUsage,
                  "tolerance must be a finite number >= 0, got '" + g(t[k]) + "'",
                  Place{.option = option}, {t[k]});
}

}  // namespace sfit
