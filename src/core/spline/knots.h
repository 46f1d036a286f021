// Uniform knot vectors and Greville abscissae (docs/method.md section 2, section 3 step 1).
#pragma once

#include <vector>

namespace sfit {

/// Full clamped uniform knot vector of a curve of `degree` with `count` control points
/// (count >= degree + 1): degree+1 zeros, the integers 1 ... count-degree-1, degree+1 copies
/// of count-degree. Length count + degree + 1; domain [0, count - degree].
std::vector<double> clamped_uniform_knots(int degree, int count);

/// Full periodic uniform knot vector of a closed curve with `count` distinct control points,
/// stored as docs/surface-json.md asks: count + degree control points (the last `degree` repeat
/// the first), knots i - degree for i = 0 ... count + 2*degree. Domain [0, count].
std::vector<double> periodic_uniform_knots(int degree, int count);

/// Parameter domain [begin, end] of a uniform curve: [0, count - degree] open, [0, count] closed.
double domain_end(int degree, int count, bool periodic);

/// Greville abscissa of control point i (0-based) of a uniform curve:
/// open (clamped): (knots[i+1] + ... + knots[i+degree]) / degree; degree 0 gives i + 0.5.
/// periodic: i - (degree - 1) / 2, reduced into [0, count).
double greville(int degree, int count, bool periodic, int i);

/// The Greville sequence read at a fractional 0-based index x in [0, count - 1] by linear
/// interpolation (docs/method.md section 3 step 3). For periodic curves the sequence is
/// extended uniformly, so x may be any real number; the result is reduced into [0, count).
double greville_at(int degree, int count, bool periodic, double x);

}  // namespace sfit
