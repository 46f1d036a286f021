// One row rule's search of the surface method (surface_method.cpp): the least-squares pairs,
// searched on all points or on a sample (pair_search.h, sampled_search.h), then minimax below
// them where the norm allows (minimax.h). Private.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "few_rows.h"
#include "fit_frame.h"
#include "search_frame.h"
#include "sfit/surface_fit.h"

namespace sfit::detail {

class FitMonitor;

/// A surface the search made: its rule, norm and where the search stopped.
struct Candidate {
  Parametrization rule = Parametrization::kUniform;
  FitNorm norm = FitNorm::kL2;
  int nu = 0, nv = 0;
  std::string stop;
};

/// What every rule's search shares: the frame, the rows' options, and what the search keeps.
struct RowRuleSearch {
  const Frame& fr;
  const FewRows& few;
  const FitOptions& o;   // the caller's
  const FitOptions& os;  // the search's problems (FewRows::options())
  std::span<const double> seam_offsets;
  std::size_t step;       // search on every step-th point of each row (1: on all)
  const FitResult* base;  // the two stages' surface where it was made
  KeptSurfaces& kept;     // no pair solved twice
  FitMonitor* monitor;
  bool linf_may;         // minimax may be tried (the norm allows it; no weights)
  long over_budget = 0;  // pairs not solved: over the solve budget
  long tried = 0;        // pairs solved
};

/// The fewest pair of `rule` below `bound`, or nothing. Where one is found, `u` and `v` get its
/// parameters (the positions along the rows and of the rows) as judged on every point.
std::optional<Candidate> search_row_rule(RowRuleSearch& rs, Parametrization rule, long bound,
                                         std::vector<double>& u, std::vector<double>& v);

}  // namespace sfit::detail
