// One row of points and its fitted curve (the curve stage, docs/method.md section 3) with the
// tolerance band, in three 2D projections and a plot of the per-axis deviations.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "sfit/curve_fit.h"
#include "sfit/render/image.h"
#include "sfit/rows.h"

namespace sfit::render {

struct RowPictureOptions {
  int width = 960, height = 720;   ///< 256 ... 4096
  int supersample = 3;             ///< 1 ... 4
  std::vector<std::string> title;  ///< lines printed at the top (UTF-8)
};

/// One 2D view: picture pixel = origin + scale * (p[axis_a], -p[axis_b]).
struct RowPanel {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< where it is on the picture
  int axis_a = 0, axis_b = 1;          ///< horizontal and vertical axes (0 = x, 1 = y, 2 = z)
  double scale = 1;
  double origin_x = 0, origin_y = 0;
};

struct RowPicture {
  Image image;
  RowPanel panels[3];                                      ///< (x, y), (x, z), (y, z)
  int plot_x0 = 0, plot_y0 = 0, plot_x1 = 0, plot_y1 = 0;  ///< the deviation plot's frame
  long worst_index = -1;  ///< point with the largest |C(t) - D| / bound
  double worst_ratio = 0;
};

/// Draws `points` (one row, in order), the curve of `fit` (fitted to them) and, around it, the
/// band in which a point may lie: the curve swept by the box of +-bound per axis, as seen in
/// each projection. The fourth panel plots (C(t_j) - D_j)_a / bound_a for each axis a against
/// the point index j, with the lines +-1 (absolute deviations where a bound is 0). A periodic
/// curve (a closed row) is drawn closed.
/// Throws Error(kUsage) for a size out of range and Error(kInternal) if `fit` does not belong
/// to `points`.
RowPicture render_row(std::span<const Point> points, const CurveFit& fit, const Point& bound,
                      const RowPictureOptions& options);

}  // namespace sfit::render
