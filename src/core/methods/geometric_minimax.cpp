#include "geometric_minimax.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "fit_frame.h"
#include "minimax.h"

namespace sfit::detail {

std::optional<GeometricFit> geometric_minimax(const Frame& fr, const FitOptions& o,
                                              const ScatteredSpec& spec, const Fractions& f,
                                              const PairOracle& searched, long bound,
                                              BasePlane plane, const GeometricLeastSquares& ls,
                                              long& tried) {
  if (o.norm == FitNorm::kL2 || weights_matter(fr.centred)) return std::nullopt;
  std::vector<std::pair<long, std::pair<int, int>>> near;
  // Where none is within kLinfReach: the pair least squares missed least, if within
  // kGeometricLinfLooseReach.
  std::pair<int, int> loose{0, 0};
  double loose_ratio = kGeometricLinfLooseReach;
  for (const auto& [pair, verdict] : searched.verdicts()) {
    const long n = static_cast<long>(pair.first) * pair.second;
    if (n >= bound || n > kGeometricLinfUnknowns || !std::isfinite(verdict.ratio)) continue;
    if (o.norm == FitNorm::kAuto && verdict.ratio > kLinfReach) {
      if (verdict.ratio <= loose_ratio) loose = pair, loose_ratio = verdict.ratio;
      continue;
    }
    near.push_back({n, pair});
  }
  if (near.empty() && loose.first > 0)
    near.push_back({static_cast<long>(loose.first) * loose.second, loose});
  if (near.empty()) return std::nullopt;
  std::sort(near.begin(), near.end());
  // At the search's parameters, then at the coordinate plane's where that plane is another:
  // there the height, and so the noise, is on one axis alone (range_hole_noise: 19 x 19
  // holds over the coordinate plane, misses by 1.15 T over the best plane).
  std::optional<Fractions> axis;
  if (plane != BasePlane::kAxis)
    axis = base_surface_fractions(fr.centred, o.closed_u, o.closed_v, BasePlane::kAxis);
  for (const Fractions* fp : {&f, axis ? static_cast<const Fractions*>(&*axis) : nullptr}) {
    if (!fp) continue;
    const ScatteredProblem full(fr.centred, spec, fp->u, fp->v);
    const std::size_t count = std::min<std::size_t>(near.size(), kGeometricLinfTries);
    for (std::size_t k = 0; k < count; ++k) {
      const auto [nu, nv] = near[k].second;
      GeometricTry t = ls(full, nu, nv);
      ++tried;
      if (t.s.control.empty()) continue;
      const std::vector<double> u = full.u_at(nu), v = full.v_at(nv);
      const bool by_l2 = t.holds;  // on every point (the search may have judged a sample)
      if (!by_l2) {
        if (!minimax_refine_points(fr.centred, u, v, o.tolerance, t.s)) continue;
        if (!judge_with_guards(fr, t.s, u, v).verdict.holds) continue;
      }
      GeometricFit out;
      out.surface = std::move(t.s);
      out.u = u;
      out.v = v;
      out.smoothing = t.smoothing;
      out.norm = by_l2 ? FitNorm::kL2 : FitNorm::kLinf;
      out.stop =
          std::string(by_l2 ? "least squares on every point" : "minimax") +
          " at the nearest pair, where no pair held by least squares (" + std::to_string(nu) +
          " x " + std::to_string(nv) +
          (fp == &f ? ")" : ", parameters from the coordinate plane nearest the best plane)");
      return out;
    }
  }
  return std::nullopt;
}

}  // namespace sfit::detail
