// The result of a surface of the geometric rule (geometric_search.h: assemble_geometric()):
// its shape measured on the surface, each row's v, and the report's rule and norm.
#include <algorithm>
#include <utility>
#include <vector>

#include "fit_frame.h"
#include "geometric_search.h"

namespace sfit::detail {

FitResult assemble_geometric(const Frame& fr, GeometricFit g, const DeviationCheck& c,
                             const FitOptions& o) {
  ShapeMeasures m;
  m.fold = geometric_fold(g.surface);
  // The box excursion on a 64 x 64 grid of the surface.
  const BoundingBox& b = fr.centred_box;
  const double ue = g.surface.u_end(), ve = g.surface.v_end();
  for (int i = 0; i <= 64; ++i)
    for (int k = 0; k <= 64; ++k) {
      const Point p = g.surface.evaluate(ue * i / 64, ve * k / 64);
      const Point out = (p - b.max).cwiseMax(b.min - p).cwiseMax(0.0);
      m.box_excursion = std::max(m.box_excursion, out.norm());
    }
  // Each row's v: the mean of its points' v (for what reads one v per row).
  std::vector<double> row_v(fr.centred.size(), 0.0);
  const auto& off = fr.centred.offsets();
  for (std::size_t j = 0; j < row_v.size(); ++j) {
    double sum = 0;
    for (std::size_t k = off[j]; k < off[j + 1]; ++k) sum += g.v[k];
    row_v[j] = off[j + 1] > off[j] ? sum / static_cast<double>(off[j + 1] - off[j]) : 0.0;
  }
  FitResult out = frame_result(std::move(g.surface), std::move(g.u), std::move(row_v), FitReport{},
                               c, m, fr.centred, fr.centre, fr.roundoff, o);
  out.v_points = std::move(g.v);
  out.report.method = FitMethod::kSurface;
  out.report.parametrization = Parametrization::kGeometric;
  out.report.parametrization_across = Parametrization::kGeometric;
  out.report.norm = g.norm;
  return out;
}

}  // namespace sfit::detail
