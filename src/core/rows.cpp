#include "sfit/rows.h"

namespace sfit {

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
