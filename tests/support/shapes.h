// Generated data sets shaped like the closed sections sfit meets (the teapot's body, handle
// and spout, a fuselage), so that tests need no data of restricted licence.
#pragma once

#include <cstdint>

#include "sfit/rows.h"

namespace sfit::test {

/// A body of revolution like a teapot's: 24 closed rings of 40 ... 56 points (ragged), from
/// the base up to the lid rim.
Rows teapot_body_like();
/// A handle like a teapot's: an elliptical tube swept along a C-shaped arc, 20 rings of 24.
Rows teapot_handle_like();
/// A spout like a teapot's: a tapering tube bending upwards, 16 rings of 20 ... 28 points.
Rows teapot_spout_like();
/// A fuselage: a nose, a cylinder and an upswept tail cone, 28 egg-shaped rings of 36 ... 44
/// points along x (metres, 37.5 long), the rings unevenly spaced, two of them 5 cm apart.
Rows fuselage_like();

/// Hard-chine hull stations drawn from `seed` (open rows along x, metres): keel -> bottom ->
/// chine -> a short flare -> knuckle -> side -> deck corner -> deck to the centre line, every
/// corner sharp. Beam, deadrise, the knuckle's height above the chine (0.15 ... 0.6 m), the
/// flare's and the side's slopes (so the knuckle turns by about 15 ... 50 degrees) and a bow
/// that narrows over the last 30 ... 50 % are random; 150 ... 400 points a row, spaced
/// unevenly; every third row has a gap of a few samples across its knuckle or deck corner.
Rows hull_stations(int stations, std::uint32_t seed);

/// Each closed row started at a random point (seeded), and every other row also reversed
/// when `reverse` is set.
Rows rotated_copy(const Rows& rows, std::uint32_t seed, bool reverse);
/// Every other row reversed (open rows).
Rows every_other_reversed(const Rows& rows);

}  // namespace sfit::test
