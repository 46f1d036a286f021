#include "shapes.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include <Eigen/Geometry>

namespace sfit::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Rings around a path c(t), t in [0,1], of radii (a(t), b(t)) in the plane spanned by the
// path's normal (in the plane of the path, normal to `up` x tangent) and `up`.
Rows tube(const std::function<Point(double)>& c, const std::function<double(double)>& a,
          const std::function<double(double)>& b, const Point& up, int rings,
          const std::function<int(int)>& points) {
  Rows out;
  for (int j = 0; j < rings; ++j) {
    const double t = static_cast<double>(j) / (rings - 1);
    const double h = 1e-5;
    const Point tangent = (c(std::min(1.0, t + h)) - c(std::max(0.0, t - h))).normalized();
    const Point side = up.cross(tangent).normalized();
    const Point normal = tangent.cross(side).normalized();
    const int n = points(j);
    for (int k = 0; k < n; ++k) {
      const double th = 2 * kPi * k / n;
      out.push_point(c(t) + a(t) * std::cos(th) * side + b(t) * std::sin(th) * normal);
    }
    out.end_row();
  }
  return out;
}

}  // namespace

Rows teapot_body_like() {
  Rows out;
  const int rings = 24;
  for (int j = 0; j < rings; ++j) {
    const double z = 0.05 + 1.45 * j / (rings - 1);
    const double r = 0.8 + 0.7 * std::sin(kPi * (0.15 + 0.75 * z / 1.5)) - 0.1 * z;
    const int n = 40 + (j * 7) % 17;
    // Each ring starts near the x axis, within 0.3 of its point spacing, as cut sections do.
    const double start = 0.3 * 2 * kPi / n * std::sin(1.7 * j);
    for (int k = 0; k < n; ++k) {
      const double th = start + 2 * kPi * k / n;
      out.push_point(Point(r * std::cos(th), r * std::sin(th), z));
    }
    out.end_row();
  }
  return out;
}

Rows teapot_handle_like() {
  // A C-shaped arc behind the body (x < 0), from the top down.
  auto c = [](double t) {
    const double a = kPi * (0.35 + 1.1 * t);
    return Point(-1.5 - 0.55 * std::sin(a), 0.0, 0.85 + 0.5 * std::cos(a));
  };
  return tube(
      c, [](double) { return 0.09; }, [](double) { return 0.05; }, Point(0, 1, 0), 20,
      [](int) { return 24; });
}

Rows teapot_spout_like() {
  auto c = [](double t) { return Point(1.3 + 0.9 * t, 0.0, 0.35 + 0.2 * t + 0.8 * t * t); };
  return tube(
      c, [](double t) { return 0.22 - 0.13 * t; }, [](double t) { return 0.2 - 0.12 * t; },
      Point(0, 1, 0), 16, [](int j) { return 20 + (j * 3) % 9; });
}

Rows fuselage_like() {
  // Ring stations along x: dense at the nose, two rings 5 cm apart mid-body, sparse elsewhere.
  const std::vector<double> x = {0.3,  0.8,  1.5,  2.4,   3.5,  4.8,  6.3,  8.0,  10.0, 12.5,
                                 15.0, 17.5, 18.0, 18.05, 20.0, 22.5, 25.0, 27.0, 28.8, 30.4,
                                 31.8, 33.0, 34.0, 34.9,  35.7, 36.4, 37.0, 37.5};
  Rows out;
  for (std::size_t j = 0; j < x.size(); ++j) {
    const double s = x[j];
    // Radius: a rounded nose to 2 m, the cylinder, a tail cone to 0.3 m.
    double r = 2.0;
    if (s < 6.3) r = 2.0 * std::sqrt(1 - std::pow(1 - s / 6.3, 2));
    if (s > 25.0) r = 2.0 - 1.7 * (s - 25.0) / 12.5;
    const double zc = s > 25.0 ? 1.4 * std::pow((s - 25.0) / 12.5, 1.5) : 0.0;  // upsweep
    const int n = 36 + static_cast<int>(j * 5) % 9;
    for (int k = 0; k < n; ++k) {
      const double th = 2 * kPi * k / n;
      // Egg-shaped: taller above the floor line than below it.
      const double y = r * std::cos(th);
      const double z = zc + r * std::sin(th) * (1.015 + 0.065 * std::sin(th));
      out.push_point(Point(s, y, z));
    }
    out.end_row();
  }
  return out;
}

Rows hull_stations(int stations, std::uint32_t seed) {
  std::mt19937 rng(seed);
  auto draw = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  const double length = draw(40, 90), beam0 = draw(4, 9), depth0 = draw(3.5, 7);
  const double dead0 = draw(8, 20), knuckle = draw(0.15, 0.6), bow = draw(0.5, 0.7);
  const double flare = draw(15, 45) * kPi / 180, side = draw(65, 95) * kPi / 180;
  Rows out;
  for (int j = 0; j < stations; ++j) {
    const double s = (j + 0.5 * draw(-0.8, 0.8)) / stations, x = length * s;
    const double fore = std::max(0.0, s - bow) / (1 - bow);
    const double beam = beam0 * (1 - std::pow(fore, 1.6)) + 0.3;
    const double dead = (dead0 + 25 * fore) * kPi / 180, depth = depth0 + 0.8 * s * s;
    const double cy = 0.8 * beam, cz = cy * std::tan(dead);
    const double ky = cy + knuckle / std::tan(flare), kz = cz + knuckle;
    const double ty = ky + (depth - kz) / std::tan(side);
    const std::vector<Point> corner = {Point(x, 0, 0), Point(x, cy, cz), Point(x, ky, kz),
                                       Point(x, ty, depth), Point(x, 0, depth + 0.1)};
    std::vector<double> arc{0};
    for (std::size_t k = 1; k < corner.size(); ++k)
      arc.push_back(arc.back() + (corner[k] - corner[k - 1]).norm());
    const int n = std::uniform_int_distribution<int>(150, 400)(rng);
    std::vector<double> t{0};
    for (int i = 1; i < n; ++i) t.push_back(t.back() + draw(0.3, 1.7));
    const double spacing = arc.back() / t.back();
    // Every third row: no samples within 1.5 spacings of its knuckle (or deck corner).
    const double gap_at = j % 3 != 0 ? -1 : arc[j % 2 == 0 ? 2 : 3];
    for (double ti : t) {
      const double a = ti / t.back() * arc.back();
      if (gap_at >= 0 && std::abs(a - gap_at) < 1.5 * spacing) continue;
      std::size_t k = 1;
      while (k + 1 < arc.size() && arc[k] < a) ++k;
      const double f = std::clamp((a - arc[k - 1]) / (arc[k] - arc[k - 1]), 0.0, 1.0);
      out.push_point((1 - f) * corner[k - 1] + f * corner[k]);
    }
    out.end_row();
  }
  return out;
}

Rows rotated_copy(const Rows& rows, std::uint32_t seed, bool reverse) {
  std::mt19937 rng(seed);
  Rows out;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const auto r = rows[j];
    const std::size_t n = r.size();
    const std::size_t s = std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
    std::vector<Point> p(n);
    for (std::size_t k = 0; k < n; ++k) p[k] = r[(s + k) % n];
    if (reverse && j % 2 == 1) std::reverse(p.begin(), p.end());
    out.add_row(p);
  }
  return out;
}

Rows every_other_reversed(const Rows& rows) {
  Rows out;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    std::vector<Point> p(rows[j].begin(), rows[j].end());
    if (j % 2 == 1) std::reverse(p.begin(), p.end());
    out.add_row(p);
  }
  return out;
}

}  // namespace sfit::test
