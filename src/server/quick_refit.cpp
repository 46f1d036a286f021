#include "quick_refit.h"

namespace sfit::server {

FitOptions quick_refit_options(const FitOptions& full, const FitReport& last) {
  FitOptions q = full;
  q.search = CountSearch::kKnown;
  q.row_count_hints = last.row_counts;
  q.column_count_hints = last.column_counts;
  q.parametrization = last.parametrization;  // kFewest's pick, not four fits
  q.progress = {};
  return q;
}

}  // namespace sfit::server
