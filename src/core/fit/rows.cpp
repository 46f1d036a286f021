#include "sfit/rows.h"
#include "sfit/weights.h"

#include <cstdio>

namespace sfit {

std::string weight_error(double w) {
  if (w >= kMinWeight && w <= kMaxWeight) return {};
  char buf[96];
  std::snprintf(buf, sizeof buf, "weight must be a number %g ... %g, got %g", kMinWeight,
                kMaxWeight, w);
  return buf;
}

BoundingBox bounding_box(const Rows& rows) {
  BoundingBox b;
  const auto& pts = rows.points();
  if (pts.empty()) return b;
  b.min = b.max = pts.front();
  for (const Point& p : pts) {
    b.min = b.min.cwiseMin(p);
    b.max = b.max.cwiseMax(p);
  }
  return b;
}

}  // namespace sfit
