#include "influence.h"

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "api_json.h"
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
  std::string why;
  const auto frozen = session.frozen(&why);  // built once per full fit (sfit/frozen_refit.h)
  if (!frozen) return no(why);

  const auto t0 = std::chrono::steady_clock::now();
  const FitResult base = frozen->refit(rows);
  const std::vector<double> g0 = frozen->influence(row, index);
  const Point p0 = rows[row][index];
  // The map checked: a move of a hundredth of the data's size (large against round-off)
  // refitted must move the control points by g d, on x, y and z alike.
  const double h = std::max(1e-2 * bounding_box(rows).diagonal(), 1e-300);
  const Point step(h, 2 * h, -h);
  const FitResult f = frozen->refit(moved(rows, row, index, p0 + step));
  const Surface& s = base.surface;
  const std::vector<Point> a = full_points(s), b = full_points(f.surface);
  std::vector<double> g(a.size());
  for (int i = 0, k = 0; i < s.full_count_u(); ++i)
    for (int l = 0; l < s.full_count_v(); ++l, ++k)
      g[k] = g0[static_cast<std::size_t>(i % s.count_u) * s.count_v + l % s.count_v];
  double big = 0, off = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const Point d = (b[k] - a[k]).cwiseQuotient(step);
    big = std::max(big, std::abs(g[k]));
    off = std::max({off, std::abs(d.x() - g[k]), std::abs(d.y() - g[k]), std::abs(d.z() - g[k])});
  }
  if (!(off <= 1e-9 * big))
    return no("the quick refit is not the map g d on x, y and z (off by " + std::to_string(off) +
              " of " + std::to_string(big) + ")");
  j["linear"] = true;
  j["point"] = {p0.x(), p0.y(), p0.z()};
  j["surface"] = packed_surface_json(base.surface, Pack::kF64);
  j["influence"] = base64(reinterpret_cast<const unsigned char*>(g.data()), g.size() * sizeof g[0]);
  j["frozen_seconds"] = frozen->seconds();  // its factorisation, once per full fit
  j["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return j;
}

}  // namespace sfit::server
