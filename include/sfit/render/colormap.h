// The colour scales of the pictures: a sequential one for deviations, a diverging one for
// curvature (both piecewise linear through published anchor colours).
#pragma once

#include "sfit/render/image.h"

namespace sfit::render {

/// Deviation relative to the tolerance, t in [0, 1] (clamped): ColorBrewer's YlOrRd (Harrower
/// and Brewer 2003), pale yellow at 0 through orange to dark red at 1 = T, so the points that
/// use most of their tolerance stand out. Its lightness falls monotonically, so a colour maps
/// back to one t.
Rgb sequential(double t);

/// The colour of a point beyond its tolerance (t > 1): magenta, outside both scales.
inline constexpr Rgb kExceeded{255, 0, 255};

/// Signed value relative to the scale, t in [-1, 1] (clamped): Moreland's cool-warm, blue for
/// negative, light grey for zero, red for positive.
Rgb diverging(double t);

/// Where a value is undefined (a degenerate normal at a pole): mid grey.
inline constexpr Rgb kUndefined{128, 128, 128};

}  // namespace sfit::render
