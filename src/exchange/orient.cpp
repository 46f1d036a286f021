// Normal orientation of a mesh: outward for closed surfaces, up for height fields.
#include <Eigen/Geometry>
#include <algorithm>
#include <unordered_set>

#include "sfit/error.h"
#include "sfit/exchange/tessellate.h"
#include "surface_frame.h"

namespace sfit::exchange {

namespace {

// Six times the volume the triangles enclose, each open end capped by a fan to the mean of
// its vertices, in coordinates centred and scaled by the mesh's size (scale-free). Positive
// when the triangles wind counter-clockwise seen from outside.
double capped_volume(const Mesh& m) {
  Point lo = m.vertices.front(), hi = lo;
  for (const Point& p : m.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Point c = lo / 2 + hi / 2;
  double size = (hi / 2 - lo / 2).cwiseAbs().maxCoeff();
  if (!(size > 0)) return 0;
  std::vector<Point> p(m.vertices.size());
  for (std::size_t k = 0; k < p.size(); ++k) p[k] = (m.vertices[k] - c) / size;
  double vol = 0;
  std::unordered_set<std::uint64_t> directed;
  auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t{a} << 32) | b; };
  for (const auto& t : m.triangles) {
    vol += p[t[0]].dot(p[t[1]].cross(p[t[2]]));
    for (int k = 0; k < 3; ++k) directed.insert(key(t[k], t[(k + 1) % 3]));
  }
  // The open ends of a grid closed in one direction: the first and last line of samples
  // across the open direction.
  if (m.periodic_u == m.periodic_v) return vol;
  const auto end_of = [&](std::uint32_t k) {
    const int line =
        m.periodic_u ? static_cast<int>(k) / m.samples_u : static_cast<int>(k) % m.samples_u;
    return line == 0 ? 0 : 1;
  };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges[2];
  Point centre[2] = {Point::Zero(), Point::Zero()};
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (directed.count(key(b, a))) continue;
      edges[end_of(a)].emplace_back(a, b);
      centre[end_of(a)] += p[a];
    }
  for (int e = 0; e < 2; ++e) {
    if (edges[e].empty()) continue;
    const Point q = centre[e] / static_cast<double>(edges[e].size());
    for (const auto& [a, b] : edges[e]) vol += q.dot(p[b].cross(p[a]));
  }
  return vol;
}

// +1 / -1 when every normal's z has that sign (a graph over xy, as seen from its normals),
// 0 otherwise.
int height_field_sign(const Mesh& m) {
  bool up = true, down = true;
  for (const Point& n : m.normals) {
    up = up && n.z() > 1e-6;
    down = down && n.z() < -1e-6;
  }
  return up ? 1 : down ? -1 : 0;
}

void flip(Mesh& m) {
  for (Point& n : m.normals) n = -n;
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  m.flipped = !m.flipped;
}

}  // namespace

NormalRule parse_normal_rule(const std::string& name) {
  if (name == "auto") return NormalRule::kAuto;
  if (name == "flip") return NormalRule::kFlip;
  if (name == "uv") return NormalRule::kData;
  throw Error(
      ErrorCode::kUsage,
      "'" + name + "' is not one of auto (outward / up), flip (the opposite), uv (S_u x S_v)",
      Place{.option = "--normals"});
}

void orient(Mesh& m, NormalRule rule) {
  if (m.flipped) flip(m);  // start from S_u x S_v
  m.orientation = "as the data runs (S_u x S_v)";
  if (rule == NormalRule::kData || m.vertices.empty()) return;
  bool turn = false;
  if (m.periodic_u || m.periodic_v) {
    turn = capped_volume(m) < 0;
    m.orientation = std::string("outward (closed in ") +
                    (m.periodic_u && m.periodic_v ? "u and v"
                     : m.periodic_u               ? "u"
                                                  : "v") +
                    ")";
  } else if (const int sign = height_field_sign(m); sign != 0) {
    turn = sign < 0;
    m.orientation = "up (+z, a height field)";
  }
  if (rule == NormalRule::kFlip) {
    turn = !turn;
    m.orientation = "flipped: opposite of " + m.orientation;
  }
  if (turn) flip(m);
}

Mesh make_mesh(const Surface& s, int samples, double tolerance, NormalRule rule) {
  Mesh m;
  if (samples != 0) {
    m = tessellate(s, samples, samples);
  } else {
    const Density d = choose_density(s, default_chord(s, tolerance), 4096, kDefaultTriangleBudget);
    m = tessellate(s, d.samples_u, d.samples_v);
    m.chordal_bound = d.bound;
  }
  orient(m, rule);
  return m;
}

}  // namespace sfit::exchange
