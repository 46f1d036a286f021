// Lawson-style reweighted least squares at a pair of Parametrization::kGeometric that misses T
// by a little (docs/method.md 7.9): the least-squares fit minimises the sum of the squared
// residuals, not the worst one, and the rule's data (10^4 and more points) is beyond the
// minimax LP (minimax_affordable()). Private to the surface search.
//
// PURPOSE  A surface at the same pair (nu, nv), smoothness weight and parameters whose worst
//          residual relative to T is lower than the least-squares one's: enough to hold T at
//          pairs where least squares misses it by up to kReweightReach.
// METHOD   Rounds of the scattered least squares (ScatteredProblem::assemble() with a weight
//          per point): each point's weight multiplied by its residual relative to T (e_k, the
//          ellipsoid norm |(S - D) / T| the check uses), normalised to mean 1 and held above
//          kReweightFloor, so the points that miss most pull hardest (Lawson's iteration for
//          the minimax fit). Stops at the first surface that holds (`holds`: the caller's
//          check of every point, guards and fold), after kReweightRounds, or when the worst
//          e_k stops falling.
// LIMITS   It does not reach the minimax fit (minimax.h: a naive reweighting stalls short of
//          it); it only pulls the worst residual down by some percent. The floor keeps every
//          point in the data term, so the smoothness term and the data still decide the spans
//          as in the plain fit (no span held by points loses them).
#pragma once

#include <cstddef>
#include <functional>

#include "scattered_lsq.h"

namespace sfit::detail {

/// Pairs whose least-squares fit misses T by at most this factor (the worst |S - D| / T per
/// axis) are reweighted.
inline constexpr double kReweightReach = 1.5;
/// The most rounds (each one assembly, factorisation and check of every point).
inline constexpr int kReweightRounds = 8;
/// Only on data of at least this many points: below it the minimax LP (minimax.h) reaches
/// more pairs, and on the example sets below it (10^3 ... 5 10^3 points) the reweighted search
/// cost 1.1-3.2x the instructions for counts that mostly stayed (bench/instruction_counts.py,
/// 2026-12-03), and the search's minimality by its own counts-given fit did not hold everywhere
/// (table1_synthetic at 1e-3: 16 x 21 found, 16 x 20 held given).
inline constexpr std::size_t kReweightPoints = 10000;
/// The least weight relative to the mean (the points far within T keep this much pull).
inline constexpr double kReweightFloor = 0.1;

/// Reweighted fits of `sp` at (nu, nv) and relative smoothness `smoothing`, starting from the
/// least-squares surface `s` (centred, at sp.u_at(nu), sp.v_at(nv)); `semi`: T per axis (with
/// the round-off allowance where T is 0). true: `s` replaced by the first surface that
/// `holds`; false: `s` unchanged.
bool reweight(const ScatteredProblem& sp, int nu, int nv, double smoothing, const Point& semi,
              Surface& s, const std::function<bool(const Surface&)>& holds);

}  // namespace sfit::detail
