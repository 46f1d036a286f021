// The one checker every tool's surface goes through: for each data point, the distance to the
// closest point of the surface (not the deviation at the tool's own parameters, which every
// tool computes differently or not at all).
#pragma once

#include <Geom_BSplineSurface.hxx>
#include <cstddef>
#include <vector>

#include "sfit/rows.h"

namespace sfit::peers {

struct CheckResult {
  std::size_t points = 0;
  double max_distance = 0;           ///< max over the points of the closest-point distance
  std::size_t out_of_tolerance = 0;  ///< points whose closest-point distance exceeds the tolerance
  long worst_row = -1;               ///< where max_distance is reached
  long worst_index = -1;
  std::size_t global_searches = 0;   ///< points that needed the multi-start search
  std::size_t occt_projections = 0;  ///< points also projected by OpenCASCADE
  std::size_t occt_closer = 0;       ///< ... of which OpenCASCADE found a closer surface point
};

/// Closest-point distance of every data point to `surface`, evaluated by OpenCASCADE.
///
/// Method: the surface is sampled (3 samples per knot span each way, at most ~4e6 samples),
/// the samples go into a uniform spatial hash. Each point starts a projected Newton search
/// (Gauss-Newton where the Hessian is not positive definite; wrap-around in a periodic
/// direction, clamping otherwise) from its row neighbour's solution, or from the nearest sample
/// for a row's first point. A point whose distance then exceeds half the tolerance is searched
/// again from its 16 nearest samples. Last, OpenCASCADE's own projection
/// (GeomAPI_ProjectPointOnSurf, Extrema) runs on every point still above the tolerance and on
/// the farthest points in turn until the next one is closer than the largest distance so far;
/// the smaller of the two answers is kept (the two searches miss in different places: ours
/// on surfaces that oscillate between samples, OCCT's at periodic seams). Every reported distance
/// is the distance to an actual surface point, so it can only over-state the true closest distance
/// (if every start missed the global minimum), never under-state it.
///
/// `threads` splits the rows (results do not depend on it). If `distances` is given, it receives
/// the distance of every point, in the order of Rows::points().
CheckResult check_closest(const Handle(Geom_BSplineSurface) & surface, const Rows& rows,
                          double tolerance, int threads, std::vector<double>* distances = nullptr);

}  // namespace sfit::peers
