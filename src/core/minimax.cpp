#include "minimax.h"

namespace sfit::detail {

bool minimax_refine(const Rows&, const std::vector<double>&, const std::vector<double>&,
                    const Point&, Surface&) {
  return false;
}

bool minimax_affordable(std::size_t, int, int) {
  return false;
}

}  // namespace sfit::detail
