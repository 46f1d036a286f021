// OBJ, STL and PLY read back by an independent reader (assimp), the OBJ free-form surface
// evaluated from the file by an independent Cox-de Boor, the VTK files' structure.
#include "sfit/exchange/mesh_writers.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <gtest/gtest.h>
#include <assimp/Importer.hpp>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "exchange_cases.h"
#include "sfit/error.h"
#include "test_support.h"

namespace sfit::exchange {
namespace {

struct Counts {
  unsigned vertices = 0, faces = 0, meshes = 0;
  bool normals = true;
};

Counts read_with_assimp(const std::string& path, unsigned flags = 0) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, flags);
  Counts c;
  if (!scene) {
    ADD_FAILURE() << path << ": " << importer.GetErrorString();
    return c;
  }
  c.meshes = scene->mNumMeshes;
  for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
    c.vertices += scene->mMeshes[k]->mNumVertices;
    c.faces += scene->mMeshes[k]->mNumFaces;
    c.normals = c.normals && scene->mMeshes[k]->HasNormals();
    for (unsigned f = 0; f < scene->mMeshes[k]->mNumFaces; ++f)
      EXPECT_EQ(scene->mMeshes[k]->mFaces[f].mNumIndices, 3u);
  }
  return c;
}

TEST(MeshWriters, AssimpReadsTheExpectedVertexAndFaceCounts) {
  const std::string dir = test::temp_dir();
  for (const auto* c : test::must_pass_cases()) {
    SCOPED_TRACE(c->name);
    const Mesh m = tessellate(c->fit.surface, 31, 23);
    const unsigned V = 31 * 23, F = static_cast<unsigned>(m.triangles.size());
    write_obj_mesh(dir + "/m.obj", m);
    write_stl(dir + "/m.stl", m);
    write_ply(dir + "/m.ply", m);
    // Indexed formats keep one vertex per sample once identical vertices are joined; STL
    // stores three corners per facet by definition.
    const Counts obj = read_with_assimp(dir + "/m.obj", aiProcess_JoinIdenticalVertices);
    EXPECT_EQ(obj.vertices, V);
    EXPECT_EQ(obj.faces, F);
    EXPECT_TRUE(obj.normals);
    const Counts ply = read_with_assimp(dir + "/m.ply", aiProcess_JoinIdenticalVertices);
    EXPECT_EQ(ply.vertices, V);
    EXPECT_EQ(ply.faces, F);
    EXPECT_TRUE(ply.normals);
    const Counts stl = read_with_assimp(dir + "/m.stl");
    EXPECT_EQ(stl.faces, F);
    EXPECT_EQ(stl.vertices, 3 * F);
    EXPECT_EQ(test::read_file(dir + "/m.stl").size(), 84u + 50u * F);
  }
}

TEST(MeshWriters, AssimpSeesOurCoordinates) {
  const auto* c = test::must_pass_cases()[2];  // the blade
  const Mesh m = tessellate(c->fit.surface, 40, 30);
  const std::string dir = test::temp_dir();
  write_ply(dir + "/b.ply", m);
  write_obj_mesh(dir + "/b.obj", m);
  for (const char* name : {"/b.ply", "/b.obj"}) {
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(dir + name, aiProcess_JoinIdenticalVertices);
    ASSERT_TRUE(scene);
    const aiMesh* mesh = scene->mMeshes[0];
    // Every vertex assimp found is one of ours (assimp reads float; compare at float).
    double worst = 0;
    for (unsigned k = 0; k < mesh->mNumVertices; ++k) {
      const aiVector3D& p = mesh->mVertices[k];
      double best = 1e300;
      for (const Point& q : m.vertices) best = std::min(best, (q - Point(p.x, p.y, p.z)).norm());
      worst = std::max(worst, best);
    }
    EXPECT_LE(worst, 1e-5 * c->diagonal) << name;
  }
}

// Independent evaluation of OBJ free-form B-spline data: Cox-de Boor recursion on the knot
// vector as written in the file (The NURBS Book, eq. 2.5).
double basis(const std::vector<double>& t, int i, int p, double x) {
  if (p == 0) {
    const bool last = t[i + 1] == t.back() && x == t.back() && t[i] < t[i + 1];
    return (t[i] <= x && x < t[i + 1]) || last ? 1.0 : 0.0;
  }
  double r = 0;
  if (t[i + p] > t[i]) r += (x - t[i]) / (t[i + p] - t[i]) * basis(t, i, p - 1, x);
  if (t[i + p + 1] > t[i + 1])
    r += (t[i + p + 1] - x) / (t[i + p + 1] - t[i + 1]) * basis(t, i + 1, p - 1, x);
  return r;
}

TEST(ObjFreeform, FileEvaluatesToTheSurface) {
  const std::string dir = test::temp_dir();
  for (const auto* c : test::must_pass_cases()) {
    SCOPED_TRACE(c->name);
    const Surface& s = c->fit.surface;
    write_obj_freeform(dir + "/f.obj", s);
    std::istringstream in(test::read_file(dir + "/f.obj"));
    std::vector<Point> v;
    std::vector<long> refs;
    std::vector<double> ku, kv, range;
    int du = 0, dv = 0;
    std::string line, cstype;
    while (std::getline(in, line)) {
      std::istringstream l(line);
      std::string key;
      l >> key;
      if (key == "v") {
        double x, y, z;
        l >> x >> y >> z;
        v.emplace_back(x, y, z);
      } else if (key == "cstype") {
        l >> cstype;
      } else if (key == "deg") {
        l >> du >> dv;
      } else if (key == "surf") {
        range.resize(4);
        l >> range[0] >> range[1] >> range[2] >> range[3];
        for (long r; l >> r;) refs.push_back(r);
      } else if (key == "parm") {
        std::string dir_name;
        l >> dir_name;
        auto& k = dir_name == "u" ? ku : kv;
        for (double x; l >> x;) k.push_back(x);
      }
    }
    EXPECT_EQ(cstype, "bspline");
    EXPECT_EQ(du, s.degree_u);
    EXPECT_EQ(dv, s.degree_v);
    EXPECT_EQ(v.size(), s.control.size());
    const int nu = static_cast<int>(ku.size()) - du - 1, nv = static_cast<int>(kv.size()) - dv - 1;
    ASSERT_EQ(refs.size(), static_cast<std::size_t>(nu) * nv);
    EXPECT_EQ(nu, s.full_count_u());
    // A periodic direction references its first control points again: closed exactly.
    if (s.periodic_u) {
      for (int j = 0; j < nv; ++j)
        for (int i = 0; i < du; ++i) {
          EXPECT_EQ(refs[j * nu + s.count_u + i], refs[j * nu + i]);
        }
    }
    double worst = 0;
    for (int a = 0; a <= 20; ++a)
      for (int b = 0; b <= 20; ++b) {
        const double u = range[0] + (range[1] - range[0]) * a / 20;
        const double w = range[2] + (range[3] - range[2]) * b / 20;
        Point p = Point::Zero();
        for (int j = 0; j < nv; ++j) {
          const double bv = basis(kv, j, dv, w);
          if (bv == 0) continue;
          for (int i = 0; i < nu; ++i) p += basis(ku, i, du, u) * bv * v[refs[j * nu + i] - 1];
        }
        worst = std::max(worst, (p - s.evaluate(u, w)).norm());
      }
    EXPECT_LE(worst, 1e-12 * c->diagonal);
  }
}

template <typename T>
T big_endian_at(const std::string& s, std::size_t at) {
  char b[sizeof(T)];
  for (std::size_t k = 0; k < sizeof(T); ++k) b[k] = s[at + sizeof(T) - 1 - k];
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

TEST(VtkWriters, LegacyFileHoldsGridDataPointsAndFields) {
  const auto* c = test::must_pass_cases()[0];  // ship hull, open
  const Surface& s = c->fit.surface;
  const Mesh m = tessellate(s, 10, 8);
  const std::string dir = test::temp_dir();
  write_vtk(dir + "/h.vtk", s, m, VtkFields{true, &c->fit, &c->rows});
  const std::string t = test::read_file(dir + "/h.vtk");
  const std::size_t nd = c->rows.total_points();
  EXPECT_EQ(t.rfind("# vtk DataFile Version 3.0\n", 0), 0u);
  EXPECT_NE(t.find("\nBINARY\nDATASET POLYDATA\n"), std::string::npos);
  const std::string points = "POINTS " + std::to_string(80 + nd) + " double\n";
  const auto at = t.find(points);
  ASSERT_NE(at, std::string::npos);
  // First point: grid vertex (0, 0), big endian.
  const std::size_t p0 = at + points.size();
  EXPECT_EQ(big_endian_at<double>(t, p0), m.vertices[0].x());
  EXPECT_EQ(big_endian_at<double>(t, p0 + 16), m.vertices[0].z());
  // The first data point follows the 80 grid points.
  EXPECT_EQ(big_endian_at<double>(t, p0 + 80 * 24), c->rows.points()[0].x());
  EXPECT_NE(t.find("VERTICES " + std::to_string(nd) + " " + std::to_string(2 * nd) + "\n"),
            std::string::npos);
  EXPECT_NE(t.find("POLYGONS 63 315\n"), std::string::npos);  // 9 x 7 quads
  for (const char* a : {"NORMALS normals double", "SCALARS mean_curvature double 1",
                        "SCALARS gaussian_curvature double 1", "VECTORS deviation double",
                        "SCALARS deviation_ratio double 1"})
    EXPECT_NE(t.find(a), std::string::npos) << a;
  // deviation_ratio of the data points: max |S - D| / T, at most 1 for a fit within T, and
  // its maximum is the report's worst point.
  const auto r = t.find("SCALARS deviation_ratio double 1\nLOOKUP_TABLE default\n");
  const std::size_t r0 =
      r + std::strlen("SCALARS deviation_ratio double 1\nLOOKUP_TABLE default\n");
  // Grid points: interpolated from the data points, so within T as well.
  for (std::size_t i = 0; i < 80; ++i) {
    const double g = big_endian_at<double>(t, r0 + i * 8);
    EXPECT_TRUE(g >= 0 && g <= 1) << i << ": " << g;
  }
  double worst = 0;
  for (std::size_t i = 0; i < nd; ++i)
    worst = std::max(worst, big_endian_at<double>(t, r0 + (80 + i) * 8));
  const Point& T = c->fit.report.tolerance;
  const Point& D = c->fit.report.max_deviation;
  EXPECT_NEAR(worst, std::max({D.x() / T.x(), D.y() / T.y(), D.z() / T.z()}), 1e-9);
  EXPECT_LE(worst, 1.0);
}

TEST(VtkWriters, StructuredGridClosesPeriodicDirections) {
  const auto* c = test::must_pass_cases()[4];  // torus
  const Mesh m = tessellate(c->fit.surface, 10, 8);
  const std::string dir = test::temp_dir();
  write_vts(dir + "/t.vts", c->fit.surface, m, VtkFields{true, nullptr, nullptr});
  const std::string t = test::read_file(dir + "/t.vts");
  EXPECT_NE(t.find("<VTKFile type=\"StructuredGrid\""), std::string::npos);
  EXPECT_NE(t.find("WholeExtent=\"0 10 0 8 0 0\""), std::string::npos);  // seam repeated
  EXPECT_NE(t.find("Name=\"mean_curvature\""), std::string::npos);
  EXPECT_NE(t.find("Name=\"gaussian_curvature\""), std::string::npos);
  EXPECT_EQ(t.find("nan"), std::string::npos);
}

}  // namespace
}  // namespace sfit::exchange

namespace sfit::exchange {
namespace {

// STL holds float32: refused, naming the file and the double-precision formats, where the
// vertices would move (a far offset, a size beyond float32); nothing is written then.
TEST(MeshWriters, StlRefusesCoordinatesFloat32CannotHold) {
  const auto* c = test::must_pass_cases()[4];  // torus, size about 5
  const std::string dir = test::temp_dir();
  write_stl(dir + "/ok.stl", tessellate(c->fit.surface, 12, 8));
  EXPECT_TRUE(std::filesystem::exists(dir + "/ok.stl"));
  for (const auto& [size, offset] : std::vector<std::pair<double, double>>{
           {1.0, 1e7}, {1e-140, 0.0}, {1e140, 0.0}, {1e39, 0.0}}) {
    SCOPED_TRACE(size);
    Surface s = c->fit.surface;
    for (Point& p : s.control) p = p * size + Point::Constant(offset);
    const Mesh m = tessellate(s, 12, 8);
    try {
      write_stl(dir + "/x.stl", m);
      FAIL() << "written";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kOutputWrite);
      EXPECT_EQ(e.place().file, dir + "/x.stl");
      EXPECT_NE(e.message().find("STL stores float32"), std::string::npos);
      EXPECT_NE(e.message().find(".ply"), std::string::npos) << e.message();
    }
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.stl"));
    // The double-precision formats take it.
    write_ply(dir + "/x.ply", m);
    EXPECT_TRUE(std::filesystem::exists(dir + "/x.ply"));
  }
}

}  // namespace
}  // namespace sfit::exchange
