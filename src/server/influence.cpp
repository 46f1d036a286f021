#include "influence.h"

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "api_json.h"
#include "quick_refit.h"
#include "sfit/error.h"

namespace sfit::server {

using nlohmann::json;

namespace {

// The full control points of `s` (closed directions' wrapped ones too), as they are packed.
std::vector<Point> full_points(const Surface& s) {
  std::vector<Point> cp;
  cp.reserve(static_cast<std::size_t>(s.full_count_u()) * s.full_count_v());
  for (int i = 0; i < s.full_count_u(); ++i)
    for (int l = 0; l < s.full_count_v(); ++l) cp.push_back(s.full_at(i, l));
  return cp;
}

// `rows` with point (row, index) at `to`.
Rows moved(const Rows& rows, std::size_t row, std::size_t index, const Point& to) {
  Rows out = rows;
  out.mutable_row(row)[index] = to;
  return out;
}

}  // namespace

json drag_influence(const Session& session, std::size_t row, std::size_t index) {
  const Rows& rows = session.rows();
  if (row >= rows.size() || index >= rows[row].size())
    throw Error(ErrorCode::kUsage, "no such point",
                Place{.row = static_cast<long>(row), .point = static_cast<long>(index)});
  json j{{"version", session.version()}, {"row", row}, {"index", index}, {"linear", false}};
  const auto no = [&](const std::string& why) {
    j["why"] = why;
    return j;
  };
  if (session.dragging()) return no("a drag is under way");
  const FitOptions q = quick_refit_options(session.options(), session.result().report);
  if (q.method != FitMethod::kSurface || !q.counts)
    return no("the quick refit runs the two stages (a count per row and column)");
  if (q.parametrization != Parametrization::kUniform &&
      q.parametrization != Parametrization::kPaper)
    return no("parameters " + std::string(to_string(q.parametrization)) + " move with the point");
  if (rows.weighted()) return no("weighted rows");
  if (q.knots == KnotRule::kAdaptive)
    return no("adaptive knots (placed where the residuals concentrate: they move with the point)");
  if (q.closed_u && q.seam == SeamMode::kAlign)
    return no("closed rows aligned at their seams (the seams move with the point)");

  const auto t0 = std::chrono::steady_clock::now();
  const FitResult base = fit_surface(rows, q);
  const Point p0 = rows[row][index];
  // A move of a hundredth of the data's size: large against round-off, the same map.
  const double h = std::max(1e-2 * bounding_box(rows).diagonal(), 1e-300);
  const Point step(h, 2 * h, -h);
  const FitResult f = fit_surface(moved(rows, row, index, p0 + step), q);
  const std::vector<Point> a = full_points(base.surface), b = full_points(f.surface);
  if (a.size() != b.size() || base.surface.count_u != f.surface.count_u ||
      base.surface.count_v != f.surface.count_v || base.surface.degree_u != f.surface.degree_u ||
      base.surface.degree_v != f.surface.degree_v)
    return no("the quick refit changed the surface's shape when the point moved");
  std::vector<double> g(a.size());
  double big = 0, off = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const Point d = (b[k] - a[k]).cwiseQuotient(step);
    g[k] = d.x();
    big = std::max(big, std::abs(d.x()));
    off = std::max({off, std::abs(d.y() - d.x()), std::abs(d.z() - d.x())});
  }
  if (!(off <= 1e-9 * big))
    return no("the quick refit is not the same map on x, y and z (off by " + std::to_string(off) +
              " of " + std::to_string(big) + ")");
  j["linear"] = true;
  j["point"] = {p0.x(), p0.y(), p0.z()};
  j["surface"] = packed_surface_json(base.surface, Pack::kF64);
  j["influence"] = base64(reinterpret_cast<const unsigned char*>(g.data()), g.size() * sizeof g[0]);
  j["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return j;
}

}  // namespace sfit::server
