#include "holds_unfolded.h"

#include <gtest/gtest.h>

#include <vector>

#include "sfit/fold_check.h"
#include "surface_distance.h"
#include "test_support.h"

namespace sfit::test {

void expect_holds_unfolded(const FitResult& f, const Rows& rows, const Point& tol) {
  EXPECT_TRUE(f.report.within_tolerance);
  const Point dev = reference_deviation(f, rows);
  for (int a = 0; a < 3; ++a) EXPECT_LE(dev[a], tol[a] * (1 + 1e-9)) << "axis " << a;
  for (std::size_t k = 0; k < rows.total_points(); k += 7)
    ASSERT_LE(distance_to_surface(f.surface, rows.points()[k]), tol.x() * (1 + 1e-9))
        << "point " << k;
  const int n = 4 * f.surface.count_v + 1;
  std::vector<double> v(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) v[k] = f.surface.v_end() * k / (n - 1);
  EXPECT_LE(fold_measure(f.surface, v), kFoldRelative * bounding_box(rows).diagonal());
  EXPECT_EQ(f.report.fold, 0.0);
}

}  // namespace sfit::test
