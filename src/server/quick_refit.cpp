#include "quick_refit.h"

namespace sfit::server {

FitOptions quick_refit_options(const FitOptions& full, const FitReport& last) {
  FitOptions q = full;
  q.progress = {};
  q.cancel = nullptr;  // a drag step's refit is never the stale search a newer step drops
  q.parametrization = last.parametrization;  // the rule the full fit picked, not four fits
  if (last.method == FitMethod::kSurface) {
    // The surface search's pair, solved once by least squares: no search (FitOptions::counts)
    // and no linear program (a minimax fit costs some 10 ms at 300 points, least squares
    // 0.1 ms). Where the full fit needed minimax, or the moved point leaves the pair short, the
    // quick surface may miss T; its report says so, and the full fit follows at rest.
    q.counts = std::array<int, 2>{last.count_u, last.count_v};
    q.norm = FitNorm::kL2;
  } else {
    // The two stages (asked for, or where the search kept their surface): their counts taken
    // as the answer, one solve per row and column.
    q.method = FitMethod::kSfit01;
    q.search = CountSearch::kKnown;
    q.row_count_hints = last.row_counts;
    q.column_count_hints = last.column_counts;
  }
  return q;
}

}  // namespace sfit::server
