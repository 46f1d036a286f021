// Progress of a long fit, and how a caller stops one (FitOptions::progress and ::cancel).
#pragma once

#include <cstddef>
#include <functional>
#include <string_view>

namespace sfit {

/// What a fit is doing, passed to FitOptions::progress.
struct FitProgress {
  /// "search" (the surface search's pairs), "lower bound", "rows" (curve stage), "columns"
  /// (transverse stage), "check" (every point on the finished surface), "fold guard".
  std::string_view phase;
  std::size_t done = 0;   ///< items of the phase done (rows, columns, rules searched)
  std::size_t total = 0;  ///< items in the phase
  long pairs_tried = 0;   ///< (nu, nv) pairs the surface search solved at so far
  int best_u = 0;         ///< the fewest nu x nv found to hold so far (0: none yet)
  int best_v = 0;
  double seconds = 0;  ///< since the fit started
};

/// Called from the thread that called the fit: at the start and end of every phase, and
/// every kProgressInterval seconds while one runs. Returning false stops the fit: it throws
/// Error with ErrorCode::kCancelled at its next check, within about kProgressInterval of
/// work. The callback never changes a result.
using ProgressFunction = std::function<bool(const FitProgress&)>;

/// Seconds between two calls of a ProgressFunction inside a phase.
inline constexpr double kProgressInterval = 0.02;

}  // namespace sfit
