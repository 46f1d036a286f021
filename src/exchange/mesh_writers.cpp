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

// STL holds float32: refuse a mesh whose coordinates overflow it (inf) or whose size it
// cannot resolve (every vertex rounded onto a few float values), before anything is written.
void check_float32_range(const std::string& path, const Mesh& m) {
  Point lo = Point::Constant(INFINITY), hi = Point::Constant(-INFINITY);
  for (const Point& p : m.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (m.vertices.empty()) return;
  const double largest = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  const double size = (hi - lo).norm();
  constexpr double kMax = std::numeric_limits<float>::max();
  const double least = std::max(1e-30, largest * 1e-6);  // float32 keeps ~7 digits
  char why[200];
  if (largest > kMax)
    std::snprintf(why, sizeof why, "coordinates reach %.3g, beyond float32's %.3g", largest, kMax);
  else if (size < least)
    std::snprintf(why, sizeof why, "the surface spans %.3g, which float32 does not resolve", size);
  else
    return;
  throw Error(ErrorCode::kOutputWrite,
              std::string("cannot write output: STL stores float32 and ") + why +
                  " (write .ply, .vtk or .step instead)",
              Place{.file = path}, {largest, size});
}

void write_stl(const std::string& path, const Mesh& m) {
  check_float32_range(path, m);
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
    Point n = (b - a).cross(c - a);
    n = n.norm() > 0 ? n.normalized()
                     : Point((m.normals[t[0]] + m.normals[t[1]] + m.normals[t[2]]).normalized());
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

namespace {

struct GridFields {
  std::vector<double> mean, gaussian;
};

GridFields grid_curvature(const Surface& s, const Mesh& m) {
  GridFields g;
  g.mean.resize(m.vertices.size());
  g.gaussian.resize(m.vertices.size());
  for (int b = 0; b < m.samples_v; ++b)
    for (int a = 0; a < m.samples_u; ++a) {
      const Curvature k = curvature(s, m.u[a], m.v[b]);
      g.mean[m.index(a, b)] = k.mean;
      g.gaussian[m.index(a, b)] = k.gaussian;
    }
  return g;
}

// Legacy VTK binary data is big endian.
template <typename T>
void put_be(std::string& out, T value) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  for (std::size_t k = sizeof(T); k-- > 0;) out += b[k];
}
void put_be3(std::string& out, const Point& p) {
  for (int k = 0; k < 3; ++k) put_be<double>(out, p[k]);
}

std::string base64(const std::string& bytes) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string o;
  o.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    o += t[(v >> 18) & 63];
    o += t[(v >> 12) & 63];
    o += t[(v >> 6) & 63];
    o += t[v & 63];
  }
  if (i < bytes.size()) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    o += t[(v >> 18) & 63];
    o += t[(v >> 12) & 63];
    o += i + 1 < bytes.size() ? t[(v >> 6) & 63] : '=';
    o += '=';
  }
  return o;
}

}  // namespace

void write_vtk(const std::string& path, const Surface& s, const Mesh& m, const VtkFields& f) {
  const bool data = f.fit && f.rows && f.fit->u.size() == f.rows->total_points() &&
                    f.fit->v.size() == f.rows->size();
  const std::size_t ng = m.vertices.size();
  const std::size_t nd = data ? f.rows->total_points() : 0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Point nan3(nan, nan, nan);
  std::vector<double> du(nd), dv(nd);
  if (data) {
    std::size_t k = 0;
    for (std::size_t j = 0; j < f.rows->size(); ++j)
      for (std::size_t i = 0; i < (*f.rows)[j].size(); ++i, ++k) {
        du[k] = f.fit->u[k];
        dv[k] = f.fit->v[j];
      }
  }
  // Binary legacy format: ASCII VTK cannot carry NaN, which marks the values that do not
  // apply (deviation on the grid, curvature at a pole).
  std::string o;
  o.reserve((ng + nd) * 80 + m.triangles.size() * 12);
  o += "# vtk DataFile Version 3.0\n";
  o += kBanner;
  o += "\nBINARY\nDATASET POLYDATA\n";
  o += "POINTS " + std::to_string(ng + nd) + " double\n";
  for (const Point& p : m.vertices) put_be3(o, p);
  for (const Point& p : data ? f.rows->points() : std::vector<Point>{}) put_be3(o, p);
  o += '\n';
  if (data) {
    o += "VERTICES " + std::to_string(nd) + " " + std::to_string(2 * nd) + "\n";
    for (std::size_t i = 0; i < nd; ++i) {
      put_be<std::int32_t>(o, 1);
      put_be<std::int32_t>(o, static_cast<std::int32_t>(ng + i));
    }
    o += '\n';
  }
  const std::size_t quads = static_cast<std::size_t>(m.quads_u()) * m.quads_v();
  o += "POLYGONS " + std::to_string(quads) + " " + std::to_string(5 * quads) + "\n";
  for (int b = 0; b < m.quads_v(); ++b)
    for (int a = 0; a < m.quads_u(); ++a) {
      put_be<std::int32_t>(o, 4);
      for (auto k : {m.index(a, b), m.index(a + 1, b), m.index(a + 1, b + 1), m.index(a, b + 1)})
        put_be<std::int32_t>(o, static_cast<std::int32_t>(k));
    }
  o += "\nPOINT_DATA " + std::to_string(ng + nd) + "\n";
  o += "NORMALS normals double\n";
  for (const Point& n : m.normals) put_be3(o, n);
  for (std::size_t i = 0; i < nd; ++i) {
    Point d[6];
    s.derivatives(du[i], dv[i], d);
    const Point c = d[1].cross(d[2]);
    put_be3(o, c.norm() > 0 ? Point(c.normalized()) : nan3);
  }
  o += '\n';
  if (f.curvature) {
    const GridFields g = grid_curvature(s, m);
    std::vector<Curvature> kd(nd);
    for (std::size_t i = 0; i < nd; ++i) kd[i] = curvature(s, du[i], dv[i]);
    o += "SCALARS mean_curvature double 1\nLOOKUP_TABLE default\n";
    for (double x : g.mean) put_be<double>(o, x);
    for (const auto& k : kd) put_be<double>(o, k.mean);
    o += "\nSCALARS gaussian_curvature double 1\nLOOKUP_TABLE default\n";
    for (double x : g.gaussian) put_be<double>(o, x);
    for (const auto& k : kd) put_be<double>(o, k.gaussian);
    o += '\n';
  }
  if (data) {
    const Point& T = f.fit->report.tolerance;
    std::vector<Point> dev(nd);
    for (std::size_t i = 0; i < nd; ++i) dev[i] = s.evaluate(du[i], dv[i]) - f.rows->points()[i];
    o += "VECTORS deviation double\n";
    for (std::size_t i = 0; i < ng; ++i) put_be3(o, nan3);
    for (const Point& d : dev) put_be3(o, d);
    o += "\nSCALARS deviation_ratio double 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < ng; ++i) put_be<double>(o, nan);
    for (const Point& d : dev) {
      double r = 0;
      for (int a = 0; a < 3; ++a)
        r = std::max(r, T[a] > 0 ? std::abs(d[a]) / T[a] : (d[a] == 0 ? 0.0 : std::abs(d[a])));
      put_be<double>(o, r);
    }
    o += '\n';
  }
  write_text(path, o);
}

void write_vts(const std::string& path, const Surface& s, const Mesh& m, const VtkFields& f) {
  // A structured grid cannot wrap: repeat the first column/row at the end of a periodic
  // direction so the grid closes.
  const int nu = m.samples_u + (m.periodic_u ? 1 : 0);
  const int nv = m.samples_v + (m.periodic_v ? 1 : 0);
  auto array = [&](std::string& o, const char* type_name, const std::string& attributes,
                   auto&& value_of) {
    std::string raw;
    for (int b = 0; b < nv; ++b)
      for (int a = 0; a < nu; ++a) value_of(raw, m.index(a, b));
    std::string block;
    put<std::uint32_t>(block, static_cast<std::uint32_t>(raw.size()));
    o += std::string("        <DataArray type=\"") + type_name + "\" " + attributes +
         " format=\"binary\">\n          " + base64(block) + base64(raw) +
         "\n        </DataArray>\n";
  };
  std::string o;
  o += "<?xml version=\"1.0\"?>\n<!-- ";
  o += kBanner;
  o += " -->\n<VTKFile type=\"StructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt32\">\n";
  const std::string extent =
      "0 " + std::to_string(nu - 1) + " 0 " + std::to_string(nv - 1) + " 0 0";
  o += "  <StructuredGrid WholeExtent=\"" + extent + "\">\n    <Piece Extent=\"" + extent + "\">\n";
  o += "      <PointData Normals=\"normals\"";
  if (f.curvature) o += " Scalars=\"mean_curvature\"";
  o += ">\n";
  array(o, "Float64", "Name=\"normals\" NumberOfComponents=\"3\"",
        [&](std::string& r, std::uint32_t k) {
          for (int c = 0; c < 3; ++c) put<double>(r, m.normals[k][c]);
        });
  if (f.curvature) {
    const GridFields g = grid_curvature(s, m);
    array(o, "Float64", "Name=\"mean_curvature\"",
          [&](std::string& r, std::uint32_t k) { put<double>(r, g.mean[k]); });
    array(o, "Float64", "Name=\"gaussian_curvature\"",
          [&](std::string& r, std::uint32_t k) { put<double>(r, g.gaussian[k]); });
  }
  o += "      </PointData>\n      <Points>\n";
  array(o, "Float64", "NumberOfComponents=\"3\"", [&](std::string& r, std::uint32_t k) {
    for (int c = 0; c < 3; ++c) put<double>(r, m.vertices[k][c]);
  });
  o += "      </Points>\n    </Piece>\n  </StructuredGrid>\n</VTKFile>\n";
  write_text(path, o);
}

}  // namespace sfit::exchange
