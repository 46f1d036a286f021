// The VTK writers of mesh_writers.h: legacy binary POLYDATA (.vtk) and XML StructuredGrid
// (.vts), with normals, curvature (raw, clipped, and the clip range as field data) and the
// fit's deviation.
#include <Eigen/Geometry>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <ostream>

#include "mesh_fields.h"
#include "sfit/exchange/mesh_writers.h"
#include "sfit/io/atomic_file.h"
#include "surface_frame.h"
#if __has_include("sfit/version.h")
#include "sfit/version.h"
#endif

namespace sfit::exchange {

namespace {

// The banner of mesh_writers.cpp, with the generated version where the build has it.
#if __has_include("sfit/version.h")
const char* kBanner = "sfit " SFIT_VERSION_STRING " B-spline surface (Vergeest 1989, SFIT01)";
#else
const char* kBanner = "sfit 0.1.0 B-spline surface (Vergeest 1989, SFIT01)";
#endif

template <typename T>
void put(std::string& out, T value) {  // little endian, as every supported host is
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  out.append(b, sizeof(T));
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

std::string num(double x) {
  if (!std::isfinite(x)) return std::isnan(x) ? "nan" : x > 0 ? "inf" : "-inf";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
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

void write_text(const std::string& path, const std::string& text) {
  io::write_file_atomically(path, [&](std::ostream& o) {
    o.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

// Everything the two writers put on the points: grid samples first, then data points.
struct PointData {
  detail::DataPoints data;
  std::vector<Point> data_normals;
  bool curvature = false;
  detail::CurvatureFields k;
  std::vector<Point> deviation;  // grid (interpolated) then data
  std::vector<double> ratio;
};

PointData point_data(const Surface& s, const Mesh& m, const VtkFields& f) {
  const detail::SurfaceFrame frame(s);
  PointData p;
  p.data = detail::data_points(s, f.fit, f.rows);
  const std::size_t nd = p.data.points.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  p.data_normals.resize(nd);
  for (std::size_t i = 0; i < nd; ++i) {
    Point n;
    p.data_normals[i] = frame.normal_near(p.data.u[i], p.data.v[i], n)
                            ? Point(m.flipped ? -n : n)
                            : Point(nan, nan, nan);  // a genuinely degenerate point
  }
  p.curvature = f.curvature;
  if (f.curvature) p.k = detail::curvature_fields(frame, m, p.data.u, p.data.v);
  if (nd > 0) {
    p.deviation = detail::grid_deviation(s, m, p.data, *f.rows);
    p.deviation.insert(p.deviation.end(), p.data.deviation.begin(), p.data.deviation.end());
    for (const Point& d : p.deviation)
      p.ratio.push_back(detail::deviation_ratio(d, p.data.tolerance));
  }
  return p;
}

}  // namespace

void write_vtk(const std::string& path, const Surface& s, const Mesh& m, const VtkFields& f) {
  const PointData pd = point_data(s, m, f);
  const std::size_t ng = m.vertices.size(), nd = pd.data.points.size();
  std::string o;
  o.reserve((ng + nd) * 120 + m.triangles.size() * 12);
  o += "# vtk DataFile Version 3.0\n";
  o += kBanner;
  o += "\nBINARY\nDATASET POLYDATA\n";
  if (pd.curvature) {  // the robust colour ranges of the clipped curvature fields
    o += "FIELD FieldData 2\n";
    for (const auto& [name, field] : {std::pair{"mean_curvature_range", &pd.k.mean},
                                      std::pair{"gaussian_curvature_range", &pd.k.gaussian}}) {
      o += std::string(name) + " 1 2 double\n";
      put_be<double>(o, field->lo);
      put_be<double>(o, field->hi);
      o += '\n';
    }
  }
  o += "POINTS " + std::to_string(ng + nd) + " double\n";
  for (const Point& p : m.vertices) put_be3(o, p);
  for (const Point& p : pd.data.points) put_be3(o, p);
  o += '\n';
  if (nd > 0) {
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
      const std::uint32_t p = m.index(a, b), q = m.index(a + 1, b), r = m.index(a + 1, b + 1),
                          t = m.index(a, b + 1);
      for (auto k : m.flipped ? std::array{p, t, r, q} : std::array{p, q, r, t})
        put_be<std::int32_t>(o, static_cast<std::int32_t>(k));
    }
  o += "\nPOINT_DATA " + std::to_string(ng + nd) + "\n";
  o += "NORMALS normals double\n";
  for (const Point& n : m.normals) put_be3(o, n);
  for (const Point& n : pd.data_normals) put_be3(o, n);
  o += '\n';
  auto scalars = [&](const char* name, const std::vector<double>& values) {
    o += std::string("SCALARS ") + name + " double 1\nLOOKUP_TABLE default\n";
    for (double x : values) put_be<double>(o, x);
    o += '\n';
  };
  if (pd.curvature) {
    scalars("mean_curvature", pd.k.mean.values);
    scalars("gaussian_curvature", pd.k.gaussian.values);
    scalars("mean_curvature_clipped", pd.k.mean.clipped);
    scalars("gaussian_curvature_clipped", pd.k.gaussian.clipped);
  }
  if (nd > 0) {
    o += "VECTORS deviation double\n";
    for (const Point& d : pd.deviation) put_be3(o, d);
    o += '\n';
    scalars("deviation_ratio", pd.ratio);
  }
  write_text(path, o);
}

void write_vts(const std::string& path, const Surface& s, const Mesh& m, const VtkFields& f) {
  const PointData pd = point_data(s, m, f);
  // A structured grid cannot wrap: repeat the first column/row at the end of a periodic
  // direction so the grid closes. Its cells wind with x_i x x_j: when the mesh is flipped,
  // i runs backwards along u so they wind with the normals.
  const int nu = m.samples_u + (m.periodic_u ? 1 : 0);
  const int nv = m.samples_v + (m.periodic_v ? 1 : 0);
  auto array = [&](std::string& o, const std::string& attributes, auto&& value_of) {
    std::string raw;
    for (int b = 0; b < nv; ++b)
      for (int i = 0; i < nu; ++i) value_of(raw, m.index(m.flipped ? nu - 1 - i : i, b));
    std::string block;
    put<std::uint32_t>(block, static_cast<std::uint32_t>(raw.size()));
    o += "        <DataArray type=\"Float64\" " + attributes + " format=\"binary\">\n          " +
         base64(block) + base64(raw) + "\n        </DataArray>\n";
  };
  auto vectors = [&](std::string& o, const char* name, const std::vector<Point>& v) {
    array(o, std::string("Name=\"") + name + "\" NumberOfComponents=\"3\"",
          [&](std::string& r, std::uint32_t k) {
            for (int c = 0; c < 3; ++c) put<double>(r, v[k][c]);
          });
  };
  auto scalars = [&](std::string& o, const char* name, const std::vector<double>& v) {
    array(o, std::string("Name=\"") + name + "\"",
          [&](std::string& r, std::uint32_t k) { put<double>(r, v[k]); });
  };
  std::string o;
  o += "<?xml version=\"1.0\"?>\n<!-- ";
  o += kBanner;
  o += " -->\n<VTKFile type=\"StructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt32\">\n";
  const std::string extent =
      "0 " + std::to_string(nu - 1) + " 0 " + std::to_string(nv - 1) + " 0 0";
  o += "  <StructuredGrid WholeExtent=\"" + extent + "\">\n";
  if (pd.curvature) {
    o += "    <FieldData>\n";
    for (const auto& [name, field] : {std::pair{"mean_curvature_range", &pd.k.mean},
                                      std::pair{"gaussian_curvature_range", &pd.k.gaussian}})
      o += std::string("      <DataArray type=\"Float64\" Name=\"") + name +
           "\" NumberOfTuples=\"2\" format=\"ascii\">" + num(field->lo) + " " + num(field->hi) +
           "</DataArray>\n";
    o += "    </FieldData>\n";
  }
  o += "    <Piece Extent=\"" + extent + "\">\n";
  o += "      <PointData Normals=\"normals\"";
  if (pd.curvature) o += " Scalars=\"mean_curvature_clipped\"";
  if (!pd.ratio.empty()) o += " Vectors=\"deviation\"";
  o += ">\n";
  vectors(o, "normals", m.normals);
  if (pd.curvature) {
    scalars(o, "mean_curvature", pd.k.mean.values);
    scalars(o, "gaussian_curvature", pd.k.gaussian.values);
    scalars(o, "mean_curvature_clipped", pd.k.mean.clipped);
    scalars(o, "gaussian_curvature_clipped", pd.k.gaussian.clipped);
  }
  if (!pd.ratio.empty()) {  // the grid part: interpolated from the data points
    vectors(o, "deviation", pd.deviation);
    scalars(o, "deviation_ratio", pd.ratio);
  }
  o += "      </PointData>\n      <Points>\n";
  vectors(o, "Points", m.vertices);
  o += "      </Points>\n    </Piece>\n  </StructuredGrid>\n</VTKFile>\n";
  write_text(path, o);
}

}  // namespace sfit::exchange
