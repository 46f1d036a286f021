#include "sfit/render/view.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include "sfit/error.h"

namespace sfit::render {

View parse_view(const std::string& text, int up_axis, const std::string& option) {
  View v;
  v.up_axis = up_axis;
  if (text == "iso") return v;
  if (text == "front") return {0, 0, up_axis};
  if (text == "side") return {90, 0, up_axis};
  if (text == "top") return {0, 90, up_axis};
  const auto comma = text.find(',');
  double az = 0, el = 0;
  auto number = [](std::string_view s, double& x) {
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    const auto r = std::from_chars(s.data(), s.data() + s.size(), x);
    return !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(x);
  };
  if (comma == std::string::npos || !number(std::string_view(text).substr(0, comma), az) ||
      !number(std::string_view(text).substr(comma + 1), el))
    throw Error(
        ErrorCode::kUsage,
        "'" + text + "' is not a view: give iso, front, top, side or AZIMUTH,ELEVATION in degrees",
        Place{.option = option});
  if (el < -90 || el > 90)
    throw Error(ErrorCode::kUsage, "elevation must be -90 ... 90 degrees", Place{.option = option},
                {el});
  return {az, el, up_axis};
}

Camera Camera::looking(const View& view, double exaggeration) {
  const int a = view.up_axis;
  const Eigen::Vector3d e3 = Eigen::Vector3d::Unit(a);
  const Eigen::Vector3d e1 = Eigen::Vector3d::Unit((a + 1) % 3);
  const Eigen::Vector3d e2 = Eigen::Vector3d::Unit((a + 2) % 3);
  const double az = view.azimuth * std::numbers::pi / 180,
               el = view.elevation * std::numbers::pi / 180;
  Camera c;
  c.up_axis = a;
  c.exaggeration = exaggeration;
  c.toward = std::cos(el) * (std::sin(az) * e1 - std::cos(az) * e2) + std::sin(el) * e3;
  c.right = std::cos(az) * e1 + std::sin(az) * e2;
  c.up = c.toward.cross(c.right);
  return c;
}

Eigen::Vector3d Camera::project(const Point& world) const {
  const Point p = exaggerate(world);
  return {origin.x() + scale * p.dot(right), origin.y() - scale * p.dot(up), p.dot(toward)};
}

void Camera::fit(std::span<const Point> points, double x0, double y0, double x1, double y1,
                 double margin) {
  double lo_r = INFINITY, hi_r = -INFINITY, lo_u = INFINITY, hi_u = -INFINITY;
  for (const Point& p : points) {
    const double r = p.dot(right), u = p.dot(up);
    lo_r = std::min(lo_r, r);
    hi_r = std::max(hi_r, r);
    lo_u = std::min(lo_u, u);
    hi_u = std::max(hi_u, u);
  }
  if (!(hi_r >= lo_r)) lo_r = hi_r = lo_u = hi_u = 0;
  double extent = std::max(hi_r - lo_r, hi_u - lo_u);
  if (!(extent > 0)) extent = 1;  // a single point
  const double w = std::max(hi_r - lo_r, 1e-9 * extent), h = std::max(hi_u - lo_u, 1e-9 * extent);
  const double sw = (x1 - x0) * (1 - 2 * margin) / w, sh = (y1 - y0) * (1 - 2 * margin) / h;
  double s = std::min(sw, sh);
  if (!std::isfinite(s) || s <= 0) s = 1;
  scale = s;
  origin = {0.5 * (x0 + x1) - s * 0.5 * (lo_r + hi_r), 0.5 * (y0 + y1) + s * 0.5 * (lo_u + hi_u)};
}

}  // namespace sfit::render
