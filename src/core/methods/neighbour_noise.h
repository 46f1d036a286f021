// How far the points stray from the smooth surface through their neighbours (docs/method.md
// 7.12): a measure of noise that no parameter rule enters, for the report's claim that T forces
// interpolation where the rows alone cannot tell (a rule that gives each point its own v is no
// curve along a row). Private to the surface method.
#pragma once

#include <string>

#include "sfit/options.h"
#include "sfit/rows.h"

namespace sfit::detail {

/// Points predicted from their neighbours.
struct NeighbourNoise {
  long points = 0;    // points predicted (a sample spread over the rows)
  long beyond = 0;    // of them, those farther than T from their neighbours' quadric (cubic)
  double median = 0;  // the median of |miss| / T along the neighbours' normal
};

/// For up to 1024 points spread over the rows: the quadric h(s, t) fitted by least squares to
/// its neighbours (up to 6 in its own row and 5 in each of the two rows either side, nearest in
/// space, never the point itself), in the frame of their principal axes (h along the normal);
/// the point's distance from it along the normal, over what T allows along that normal
/// (sum over the axes of |n_a| T_a; an axis with T = 0 at `roundoff`). Where there are 16
/// neighbours or more the cubic is fitted too and the lesser distance counts (a quadric's own
/// error on smooth data sampled sparsely at a small T is no noise). Points whose neighbours
/// lie nearly on a line, or are too few for a quadric, are left out.
NeighbourNoise neighbour_noise(const Rows& centred, const FitOptions& o, double roundoff);

/// Whether the points' own scatter forces (near) interpolation at T whatever the parameters:
/// the median point of neighbour_noise() is farther than T from its neighbours' quadric (a
/// smooth surface through the neighbours misses most points by more than T, so any surface
/// within T must follow the points one by one). `why` gets the numbers.
bool neighbours_force_interpolation(const Rows& centred, const FitOptions& o, double roundoff,
                                    std::string& why);

/// Where the points that jump (farther than `factor` T from their neighbours' quadric) lie: how
/// many rows hold one, and how many of `bins` equal parts of a row's chord length (as many as the
/// median row has points) do. Every point of sets up to 2^18 points, a stride above.
struct JumpSpread {
  long points = 0;  // points predicted
  long jumps = 0;   // of them, farther than T from their neighbours' quadric
  long rows = 0, rows_hit = 0;
  long bins = 0, bins_hit = 0;
};
JumpSpread jump_spread(const Rows& centred, const FitOptions& o, double roundoff, double factor);

/// Whether jumps spread over the data force about as many control points as points. A jump:
/// a point farther than 2 T both from the quadric through its neighbours and from the
/// quadratic through its own row's neighbours (a surface smooth there and within T of the
/// neighbours misses it by more than T; the row's test keeps rows far apart, whose quadric is
/// loose, from counting). A step or spike beyond T needs knot lines on either side of it, along
/// the rows and across them; so where the jumps lie in at least half of the rows and across at
/// least half of a row's length (in parts as many as the median row has points), one
/// tensor-product surface needs knot lines about everywhere (a LiDAR tile's roofs and trees,
/// whose median point is calm). `why` gets the numbers where it does.
bool jumps_force_interpolation(const Rows& centred, const FitOptions& o, double roundoff,
                               std::string& why);

}  // namespace sfit::detail
