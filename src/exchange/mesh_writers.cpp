#include "sfit/exchange/mesh_writers.h"

#include <Eigen/Geometry>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <ostream>

#include "sfit/error.h"
#include "sfit/io/atomic_file.h"
#include "sfit/version.h"

namespace sfit::exchange {

namespace {

// Shortest text that reads back to the same double.
void num(std::string& out, double x) {
  if (std::isnan(x)) {
    out += "nan";
    return;
  }
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

void xyz(std::string& out, const Point& p) {
  num(out, p.x());
  out += ' ';
  num(out, p.y());
  out += ' ';
  num(out, p.z());
}

template <typename T>
void put(std::string& out, T value) {  // little endian, as every supported host is
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  out.append(b, sizeof(T));
}

void write_text(const std::string& path, const std::string& text) {
  io::write_file_atomically(path, [&](std::ostream& o) {
    o.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

const char* kBanner = "sfit " SFIT_VERSION_STRING " B-spline surface (Vergeest 1989, SFIT01)";

}  // namespace

void write_obj_freeform(const std::string& path, const Surface& s) {
  std::string o;
  o += "# ";
  o += kBanner;
  o += "\n# exact surface as OBJ free-form geometry; u along the rows, v across them\n";
  o += "# periodic: u " + std::string(s.periodic_u ? "yes" : "no") + ", v " +
       (s.periodic_v ? "yes" : "no") + " (wrap-around control points reuse the first vertices)\n";
  // Distinct control points as vertices 1 ... count_u * count_v, u fastest.
  for (int j = 0; j < s.count_v; ++j)
    for (int i = 0; i < s.count_u; ++i) {
      o += "v ";
      xyz(o, s.at(i, j));
      o += '\n';
    }
  o += "cstype bspline\n";
  o += "deg " + std::to_string(s.degree_u) + " " + std::to_string(s.degree_v) + "\n";
  o += "surf 0 ";
  num(o, s.u_end());
  o += " 0 ";
  num(o, s.v_end());
  const int fu = s.full_count_u(), fv = s.full_count_v();
  for (int j = 0; j < fv; ++j)
    for (int i = 0; i < fu; ++i) {
      const long ref = static_cast<long>(j % s.count_v) * s.count_u + (i % s.count_u) + 1;
      o += ' ';
      o += std::to_string(ref);
    }
  o += "\nparm u";
  for (double k : s.full_knots_u()) {
    o += ' ';
    num(o, k);
  }
  o += "\nparm v";
  for (double k : s.full_knots_v()) {
    o += ' ';
    num(o, k);
  }
  o += "\nend\n";
  write_text(path, o);
}

void write_obj_mesh(const std::string& path, const Mesh& m) {
  std::string o;
  o.reserve(m.vertices.size() * 80 + m.triangles.size() * 40);
  o += "# ";
  o += kBanner;
  o += "\n# tessellation " + std::to_string(m.samples_u) + " x " + std::to_string(m.samples_v) +
       " samples, " + std::to_string(m.triangles.size()) + " triangles\n";
  for (const Point& p : m.vertices) {
    o += "v ";
    xyz(o, p);
    o += '\n';
  }
  for (const Point& n : m.normals) {
    o += "vn ";
    xyz(o, n);
    o += '\n';
  }
  for (const auto& t : m.triangles) {
    o += 'f';
    for (auto k : t) {
      const std::string r = std::to_string(k + 1);
      o += ' ' + r + "//" + r;
    }
    o += '\n';
  }
  write_text(path, o);
}

void check_stl_fits(const std::string& path, const Mesh& m) {
  if (m.vertices.empty()) return;
  Point lo = m.vertices.front(), hi = lo;
  for (const Point& p : m.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double largest = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  const double size = (hi - lo).norm();
  constexpr double kMax = std::numeric_limits<float>::max();
  const double least = std::max(1e-30, largest * 1e-6);  // float32 keeps ~7 digits
  double moved = 0;  // the largest change of a coordinate rounded to float32
  if (largest <= kMax)
    for (const Point& p : m.vertices)
      for (int k = 0; k < 3; ++k)
        moved = std::max(moved, std::abs(static_cast<double>(static_cast<float>(p[k])) - p[k]));
  char why[200];
  if (largest > kMax)
    std::snprintf(why, sizeof why, "coordinates reach %.3g, beyond float32's %.3g", largest, kMax);
  else if (size < least)
    std::snprintf(why, sizeof why, "the surface spans %.3g, which float32 does not resolve", size);
  else if (moved > kStlRounding * size)
    std::snprintf(why, sizeof why,
                  "rounding to it moves vertices by up to %.3g, %.2g%% of the surface's size %.3g",
                  moved, 100 * moved / size, size);
  else
    return;
  throw Error(ErrorCode::kOutputWrite,
              std::string("cannot write output: STL stores float32 and ") + why +
                  " (write .ply, .vtk or .step instead)",
              Place{.file = path}, {largest, size});
}

void write_stl(const std::string& path, const Mesh& m) {
  check_stl_fits(path, m);
  std::string o;
  o.reserve(84 + m.triangles.size() * 50);
  std::string header = std::string(kBanner) + " tessellation";
  header.resize(80, ' ');
  o += header;  // must not start with "solid": that marks ASCII STL
  put<std::uint32_t>(o, static_cast<std::uint32_t>(m.triangles.size()));
  for (const auto& t : m.triangles) {
    const Point& a = m.vertices[t[0]];
    const Point& b = m.vertices[t[1]];
    const Point& c = m.vertices[t[2]];
    Point n = m.normals[t[0]] + m.normals[t[1]] + m.normals[t[2]];  // if the facet is degenerate
    const Point e1 = b - a, e2 = c - a;
    const double s1 = e1.cwiseAbs().maxCoeff(), s2 = e2.cwiseAbs().maxCoeff();
    if (s1 > 0 && s2 > 0) {
      const Point f = (e1 / s1).cross(e2 / s2);  // scaled: no overflow or underflow
      if (f.norm() > 0) n = f;
    }
    n.normalize();
    for (int k = 0; k < 3; ++k) put<float>(o, static_cast<float>(n[k]));
    for (const Point* p : {&a, &b, &c})
      for (int k = 0; k < 3; ++k) put<float>(o, static_cast<float>((*p)[k]));
    put<std::uint16_t>(o, 0);
  }
  write_text(path, o);
}

void write_ply(const std::string& path, const Mesh& m) {
  std::string o;
  o += "ply\nformat binary_little_endian 1.0\ncomment ";
  o += kBanner;
  o += "\nelement vertex " + std::to_string(m.vertices.size()) + "\n";
  o += "property double x\nproperty double y\nproperty double z\n";
  o += "property float nx\nproperty float ny\nproperty float nz\n";
  o += "element face " + std::to_string(m.triangles.size()) + "\n";
  o += "property list uchar int vertex_indices\nend_header\n";
  for (std::size_t k = 0; k < m.vertices.size(); ++k) {
    for (int c = 0; c < 3; ++c) put<double>(o, m.vertices[k][c]);
    for (int c = 0; c < 3; ++c) put<float>(o, static_cast<float>(m.normals[k][c]));
  }
  for (const auto& t : m.triangles) {
    put<std::uint8_t>(o, 3);
    for (auto k : t) put<std::int32_t>(o, static_cast<std::int32_t>(k));
  }
  write_text(path, o);
}

}  // namespace sfit::exchange
