// validate_curve(): the input checks of a curve fit on its own (curve_fit.h).
#include <cmath>
#include <string>

#include "basis.h"
#include "sfit/curve_fit.h"
#include "sfit/error.h"

namespace sfit {

void validate_curve(std::span<const Point> points, const CurveFitOptions& o) {
  if (o.degree < 1 || o.degree > kMaxDegree)
    throw Error(
        ErrorCode::kUsage,
        "degree (" + std::to_string(o.degree) + ") must be 1 ... " + std::to_string(kMaxDegree),
        Place{.option = "degree"}, {static_cast<double>(o.degree)});
  for (int a = 0; a < 3; ++a)
    if (!(o.bound[a] >= 0) || !std::isfinite(o.bound[a]))
      throw Error(ErrorCode::kUsage,
                  std::string("tolerance ") + "xyz"[a] + " must be a finite number >= 0",
                  Place{.option = "tol"}, {o.bound[a]});
  if (points.empty()) throw Error(ErrorCode::kInputData, "row has no points", Place{.row = 0});
  if (o.periodic && points.size() == 2)
    throw Error(ErrorCode::kInputData,
                "a closed row needs at least 3 points (or 1 for a pole), got 2", Place{.row = 0},
                {2.0});
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!points[k].allFinite())
      throw Error(ErrorCode::kInputData, "coordinate is not a finite number",
                  Place{.row = 0, .point = static_cast<long>(k)},
                  {points[k].x(), points[k].y(), points[k].z()});
  if (!o.positions.empty() && o.positions.size() != points.size())
    throw Error(ErrorCode::kUsage,
                std::to_string(o.positions.size()) + " positions for " +
                    std::to_string(points.size()) + " points",
                Place{.option = "positions"}, {static_cast<double>(o.positions.size())});
}

}  // namespace sfit
