// Parametrization::kGeometric (docs/method.md 7.9): each point's parameters from its projection
// onto a base surface, and their correction by projection onto a fit (Hoschek). Private.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

#include "sfit/rows.h"
#include "sfit/surface.h"

namespace sfit::detail {

/// Each point's position as fractions of the domain, in rows.points() order.
struct Fractions {
  std::vector<double> u, v;
};

/// The open sheet's base plane (base_surface_fractions()) from its statistics: the points'
/// mean and their scatter about it (sum of d d^T), the rows' directions summed (each row's
/// last point minus its first), and the edge centroids of the first and the last row. u
/// runs along the rows' mean direction in the plane, v across it, growing with the rows'
/// order. nullopt where the points span no plane. A distributed fit gathers the statistics
/// over chunks and places each chunk's points with sheet_positions().
struct SheetFrame {
  Point c, along, across;
};

/// The plane an open sheet's parameters are projections onto (base_surface_fractions()).
/// kBest: the best plane of the points (least squares). kAxis: the coordinate plane nearest
/// to it (its normal the coordinate axis nearest the best plane's normal): where the data is
/// a height field over that plane, projecting onto it gives each point the parameters of
/// the function z = f(x, y) (or x = f(y, z), y = f(z, x)), the residual along that axis
/// alone. A tilted best plane shears the height field: its slopes grow on one side (on
/// bench/scan_cases.py's clipped_scan_lines, tilted 12 degrees, the worst residual at 13 x 13
/// is 1.5 T over the best plane and 0.93 T over the xy plane; docs/method.md 7.9).
enum class BasePlane { kBest, kAxis };

/// Planes within this angle (radians) of each other give the same parameters, in effect:
/// kAxis is not offered where the best plane is that near to its coordinate plane.
inline constexpr double kSamePlaneAngle = 1e-3;

/// nullopt also where `plane` is kAxis and the best plane is within kSamePlaneAngle of it.
std::optional<SheetFrame> sheet_frame(const Point& mean, const Eigen::Matrix3d& cov, Point along,
                                      const Point& first, const Point& last,
                                      BasePlane plane = BasePlane::kBest);
/// Each point's position along and across the sheet (before the scaling to [0, 1] over the
/// data: (t - min) / (max - min), clamped).
void sheet_positions(const SheetFrame& f, std::span<const Point> pts, std::span<double> u,
                     std::span<double> v);

/// The base surface's parameters, from the data alone:
/// - open rows, open across: the best plane of all points (least squares); u along the rows'
///   mean direction (first to last point, summed over the rows) projected into the plane, v
///   across it (increasing with the rows' order); both scaled to [0, 1] over the data.
/// - closed rows, open across: a swept axis through the rows' centroids (each centroid
///   weighted by edge length, so crowded points do not pull it); u = the angle around the
///   row's own plane normal, from a reference direction carried from row to row, / 2 pi in
///   [0, 1) (a row whose angle does not turn one way is placed by chord length from its
///   first point's angle); v = the distance along the centroids' path plus the point's
///   height above its row's plane, scaled to [0, 1].
/// nullopt where no base surface applies: rows closed across, fewer than 2 rows, or data
/// that spans no plane. `plane` (open rows only; kAxis with closed rows: nullopt): the
/// sheet's plane, above.
std::optional<Fractions> base_surface_fractions(const Rows& rows, bool closed_u, bool closed_v,
                                                BasePlane plane = BasePlane::kBest);

/// Parameter correction: each point's (u, v) moved to the closest point of `s` near it (up to
/// `steps` Gauss-Newton steps in (u, v), each at most one knot span, clamped into an open
/// domain, wrapped around a closed one), in place (u, v per point at s's counts).
void project_parameters(const Surface& s, const Rows& rows, std::vector<double>& u,
                        std::vector<double>& v, int steps, int threads);

}  // namespace sfit::detail
