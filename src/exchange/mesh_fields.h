// Point data for the VTK writers: curvature (scale-free, with a clipped copy and its robust
// range), and the fit's deviation at the data points and interpolated on the sample grid.
#pragma once

#include <vector>

#include "sfit/exchange/tessellate.h"
#include "sfit/rows.h"
#include "sfit/surface_fit.h"
#include "surface_frame.h"

namespace sfit::exchange::detail {

/// Percentiles of the grid values that bound the clipped copy of a curvature field.
inline constexpr double kClipLow = 0.01, kClipHigh = 0.99;

struct ScalarField {
  std::vector<double> values;   ///< grid points, then data points
  std::vector<double> clipped;  ///< values clamped to [lo, hi]
  double lo = 0, hi = 0;        ///< the kClipLow / kClipHigh percentiles of the grid values
};

struct CurvatureFields {
  ScalarField mean, gaussian;  ///< mean curvature about the mesh's (oriented) normals
};

/// Curvature at the grid's samples, then at each (u[i], v[i]) given.
CurvatureFields curvature_fields(const SurfaceFrame& frame, const Mesh& mesh,
                                 const std::vector<double>& u, const std::vector<double>& v);

/// The fit's data: the points, their (u, v), and the deviation S(u, v) - D at each.
struct DataPoints {
  std::vector<Point> points, deviation;
  std::vector<double> u, v;
  Point tolerance = Point::Zero();
};
/// Empty unless fit and rows are given and match.
DataPoints data_points(const Surface& s, const FitResult* fit, const Rows* rows);

/// The deviation on the grid: at each sample, interpolated linearly in u within the two data
/// rows around its v, then linearly in v between them (wrapping in a closed direction,
/// constant beyond the first and last row or point): a convex blend of data deviations, so
/// within T wherever the data is.
std::vector<Point> grid_deviation(const Surface& s, const Mesh& mesh, const DataPoints& data,
                                  const Rows& rows);

/// max over axes of |d| / T (|d| where T is 0).
double deviation_ratio(const Point& d, const Point& tolerance);

}  // namespace sfit::exchange::detail
