#include "surface_deviation.h"

#include <algorithm>
#include <numeric>

#include "sfit/render/colormap.h"
#include "sfit/render/deviations.h"

namespace sfit::render::detail {

std::vector<double> deviation_ratios(const Scene& sc, const RenderOptions& o) {
  const std::size_t n_points = sc.rows ? sc.rows->total_points() : 0;
  std::vector<double> ratio;
  if (o.mode != Mode::kDeviation || !n_points) return ratio;
  ratio.resize(n_points);
  for (std::size_t k = 0; k < n_points; ++k)
    ratio[k] = tolerance_ratio(sc.deviations[k], sc.tolerance, sc.zero_scale);
  return ratio;
}

void draw_deviation_points(ColorBuffer& cb, const Scene& sc, const SurfaceView& view,
                           const SurfaceRaster& r, const std::vector<double>& ratio, double radius,
                           RenderResult& res) {
  const double px = view.ss;  // one picture pixel in samples
  std::vector<std::size_t> order(ratio.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return ratio[a] < ratio[b]; });
  const DepthTest t{&r.g, r.slack, 0.f};
  const Eigen::Vector3f outline(0.3f, 0.3f, 0.3f);
  // Sparse points get a dark rim; dense ones merge into the tinted surface.
  const double rim = radius >= 2.5 ? 0.7 : 0.0;
  for (std::size_t k : order) {
    const Rgb c = ratio[k] > 1 + 1e-9 ? kExceeded : sequential(ratio[k]);
    const Eigen::Vector3d q = view.to_samples(view.cam.exaggerate(sc.rows->points()[k]));
    if (rim > 0) draw_disc(cb, q, (radius + rim) * px, outline, t);
    draw_disc(cb, q, radius * px, to_float(c), t);
  }
  if (!order.empty()) {
    res.worst_point = static_cast<long>(order.back());
    res.worst_ratio = ratio[order.back()];
    // The worst point is always shown, even where the surface hides it.
    const std::size_t k = order.back();
    const Rgb c = ratio[k] > 1 + 1e-9 ? kExceeded : sequential(ratio[k]);
    const Eigen::Vector3d q = view.to_samples(view.cam.exaggerate(sc.rows->points()[k]));
    draw_disc(cb, q, (radius + 0.7) * px, outline, {});
    draw_disc(cb, q, radius * px, to_float(c), {});
  }
}

}  // namespace sfit::render::detail
