// STEP and IGES written through OpenCASCADE and read back by OpenCASCADE's own readers
// (STEPControl_Reader, IGESControl_Reader): the surface found must evaluate like ours on a
// 50 x 50 sample of the domain, and periodic directions must come back closed.
#include <gtest/gtest.h>
#include <BRepCheck_Analyzer.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <UnitsMethods.hxx>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "exchange_cases.h"
#include "sfit/error.h"
#include "sfit/exchange/cad_writers.h"
#include "test_support.h"

namespace sfit::exchange {
namespace {

using test::FittedCase;

enum class Format { kStep, kIges };

struct ReadBack {
  int faces = 0;
  Handle(Geom_BSplineSurface) surface;
  bool valid = false;  // BRepCheck_Analyzer on the shape
};

// Reads with OCCT's session length unit set to `session_unit` (1 mm or 1000 mm), restored after.
ReadBack read_back(const std::string& path, Format f, const char* session_unit = "MM") {
  const double before = UnitsMethods::GetCasCadeLengthUnit();
  UnitsMethods::SetCasCadeLengthUnit(std::string(session_unit) == "M" ? 1000.0 : 1.0);
  struct Restore {
    double v;
    ~Restore() { UnitsMethods::SetCasCadeLengthUnit(v); }
  } restore{before};
  TopoDS_Shape shape;
  if (f == Format::kStep) {
    STEPControl_Controller::Init();
    Interface_Static::SetCVal("xstep.cascade.unit", session_unit);
    STEPControl_Reader r;
    EXPECT_EQ(r.ReadFile(path.c_str()), IFSelect_RetDone) << path;
    r.TransferRoots();
    shape = r.OneShape();
  } else {
    IGESControl_Controller::Init();
    Interface_Static::SetCVal("xstep.cascade.unit", session_unit);
    IGESControl_Reader r;
    EXPECT_EQ(r.ReadFile(path.c_str()), IFSelect_RetDone) << path;
    r.TransferRoots();
    shape = r.OneShape();
  }
  ReadBack b;
  if (shape.IsNull()) return b;
  b.valid = BRepCheck_Analyzer(shape).IsValid();
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
    ++b.faces;
    b.surface =
        Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(TopoDS::Face(e.Current())));
  }
  return b;
}

// Largest |S_ours - S_occt| over a 50 x 50 grid of the domain, relative to the diagonal.
double max_relative_deviation(const Surface& s, const Handle(Geom_BSplineSurface) & g,
                              double diagonal, double scale = 1.0) {
  double worst = 0;
  for (int a = 0; a < 50; ++a)
    for (int b = 0; b < 50; ++b) {
      const double u = s.u_end() * a / 49, v = s.v_end() * b / 49;
      const gp_Pnt q = g->Value(u, v);
      const Point d = s.evaluate(u, v) * scale - Point(q.X(), q.Y(), q.Z());
      worst = std::max(worst, d.norm() / (diagonal * scale));
    }
  return worst;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class CadRoundTrip : public ::testing::TestWithParam<Format> {};

// Open u whose first and last control-point columns are equal: a closed surface on clamped
// knots (corner knots on closed rows, docs/method.md 7.13).
bool closed_clamped_u(const Surface& s) {
  if (s.periodic_u) return false;
  for (int j = 0; j < s.count_v; ++j)
    if (s.at(0, j) != s.at(s.count_u - 1, j)) return false;
  return true;
}

void check_case(const FittedCase& c, Format f, const std::string& dir) {
  SCOPED_TRACE(c.name);
  const Surface& s = c.fit.surface;
  const std::string path = dir + "/" + (c.bundled ? "" : "data_") +
                           c.name.substr(c.name.find('/') + 1) +
                           (f == Format::kStep ? ".step" : ".igs");
  if (f == Format::kStep)
    write_step(path, s);
  else
    write_iges(path, s);
  const ReadBack b = read_back(path, f);
  ASSERT_EQ(b.faces, 1);
  ASSERT_FALSE(b.surface.IsNull()) << "the face is not on a B-spline surface";
  EXPECT_TRUE(b.valid);
  EXPECT_EQ(b.surface->UDegree(), s.degree_u);
  EXPECT_EQ(b.surface->VDegree(), s.degree_v);
  const double dev = max_relative_deviation(s, b.surface, c.diagonal);
  EXPECT_LE(dev, f == Format::kStep ? 1e-9 : 1e-8);
  std::printf("[ measure  ] %-28s %s max deviation %.3g of the diagonal\n", c.name.c_str(),
              f == Format::kStep ? "STEP" : "IGES", dev);
  // Closed directions come back closed, and periodic, so a CAD kernel sees no seam; a closed
  // u on clamped knots (corner knots on closed rows: the first and last columns one, a crease
  // at the seam) too, its two equal columns read back as one.
  const bool clamped_closed = closed_clamped_u(s);
  const bool closed_u = s.periodic_u || clamped_closed;
  EXPECT_EQ(b.surface->IsUClosed(), closed_u);
  EXPECT_EQ(b.surface->IsVClosed(), s.periodic_v);
  EXPECT_EQ(b.surface->IsUPeriodic(), closed_u);
  EXPECT_EQ(b.surface->IsVPeriodic(), s.periodic_v);
  // The same poles: distinct ones in a periodic direction.
  EXPECT_EQ(b.surface->NbUPoles(), s.count_u - (clamped_closed ? 1 : 0));
  EXPECT_EQ(b.surface->NbVPoles(), s.count_v);
}

TEST_P(CadRoundTrip, BundledOpenAndClosedSurfacesReadBackExactly) {
  const std::string dir = test::temp_dir();
  const auto cases = test::must_pass_cases();
  ASSERT_EQ(cases.size(), 5u);
  bool u = false, v = false, uv = false, open = false;
  for (const auto* c : cases) {
    check_case(*c, GetParam(), dir);
    const Surface& s = c->fit.surface;
    open |= !s.periodic_u && !closed_clamped_u(s) && !s.periodic_v;
    u |= (s.periodic_u || closed_clamped_u(s)) && !s.periodic_v;
    v |= !s.periodic_u && s.periodic_v;
    uv |= s.periodic_u && s.periodic_v;
  }
  EXPECT_TRUE(open && u && v && uv) << "all four topologies must be covered";
}

TEST_P(CadRoundTrip, DataSetsReadBackExactly) {
  const std::string dir = test::temp_dir();
  for (const auto& c : test::fitted_cases())
    if (!c.bundled) check_case(c, GetParam(), dir);
}

INSTANTIATE_TEST_SUITE_P(Formats, CadRoundTrip, ::testing::Values(Format::kStep, Format::kIges),
                         [](const auto& info) {
                           return info.param == Format::kStep ? "Step" : "Iges";
                         });

TEST(StepWriter, IsAp214WithOneAdvancedFaceAndStatedUnits) {
  const auto& c = *test::must_pass_cases()[0];
  const std::string dir = test::temp_dir();
  write_step(dir + "/mm.step", c.fit.surface);
  const std::string mm = read_text(dir + "/mm.step");
  EXPECT_NE(mm.find("FILE_SCHEMA(('AUTOMOTIVE_DESIGN"), std::string::npos);
  EXPECT_NE(mm.find("B_SPLINE_SURFACE_WITH_KNOTS"), std::string::npos);
  EXPECT_NE(mm.find("ADVANCED_FACE"), std::string::npos);
  EXPECT_NE(mm.find("SI_UNIT(.MILLI.,.METRE.)"), std::string::npos);
  EXPECT_NE(mm.find("sfit"), std::string::npos);

  write_step(dir + "/m.step", c.fit.surface, CadOptions{.units = "m"});
  const std::string m = read_text(dir + "/m.step");
  EXPECT_NE(m.find("SI_UNIT($,.METRE.)"), std::string::npos);
  // A reader in millimetres scales a file in metres by 1000: the unit is real, and the
  // numbers in the file are ours unchanged.
  const ReadBack b = read_back(dir + "/m.step", Format::kStep, "MM");
  ASSERT_FALSE(b.surface.IsNull());
  EXPECT_LE(max_relative_deviation(c.fit.surface, b.surface, c.diagonal, 1000.0), 1e-9);
  const ReadBack same = read_back(dir + "/m.step", Format::kStep, "M");
  ASSERT_FALSE(same.surface.IsNull());
  EXPECT_LE(max_relative_deviation(c.fit.surface, same.surface, c.diagonal), 1e-9);
}

TEST(StepWriter, PeriodicSurfaceIsMarkedClosed) {
  const auto cases = test::must_pass_cases();
  const std::string dir = test::temp_dir();
  write_step(dir + "/torus.step", cases[4]->fit.surface);
  const std::string t = read_text(dir + "/torus.step");
  // B_SPLINE_SURFACE_WITH_KNOTS(name, udeg, vdeg, poles, form, u_closed, v_closed, self_int, ...)
  EXPECT_NE(t.find(".UNSPECIFIED.,.T.,.T.,.F."), std::string::npos);
}

// IGES 128 parameter data: "128,K1,K2,M1,M2,PROP1,...,PROP5,".
std::vector<long> iges128_header(const std::string& text) {
  const auto at = text.find("\n128,");
  if (at == std::string::npos) return {};
  std::vector<long> v;
  std::istringstream in(text.substr(at + 1, 60));
  std::string tok;
  while (v.size() < 10 && std::getline(in, tok, ',')) v.push_back(std::stol(tok));
  return v;
}

TEST(IgesWriter, WritesEntity128WithPeriodicFlagsAndUnitWeights) {
  const auto cases = test::must_pass_cases();
  const std::string dir = test::temp_dir();
  const Surface& s = cases[1]->fit.surface;  // d150 wing: periodic u, open v
  ASSERT_TRUE(s.periodic_u && !s.periodic_v);
  write_iges(dir + "/wing.igs", s, CadOptions{.units = "m"});
  const std::string t = read_text(dir + "/wing.igs");
  const auto h = iges128_header(t);
  ASSERT_EQ(h.size(), 10u) << "no entity 128 parameter line";
  EXPECT_EQ(h[0], 128);
  EXPECT_EQ(h[3], s.degree_u);  // M1
  EXPECT_EQ(h[4], s.degree_v);  // M2
  EXPECT_EQ(h[5], 1);           // PROP1 closed in u
  EXPECT_EQ(h[6], 0);           // PROP2 open in v
  EXPECT_EQ(h[7], 1);           // PROP3 polynomial: all weights equal
  EXPECT_EQ(h[8], 1);           // PROP4 periodic in u
  EXPECT_EQ(h[9], 0);           // PROP5
  // The directory entry of a 144 trimmed surface: the face as CAD systems expect it.
  EXPECT_NE(t.find("     144"), std::string::npos);
  // Units in the global section: flag 6 = metres, name "M" (IGES 5.3 section 2.2.4.3).
  EXPECT_NE(t.find(",6,1HM,"), std::string::npos);
  // Read in metres, the numbers are ours; read in millimetres, scaled by 1000.
  const ReadBack b = read_back(dir + "/wing.igs", Format::kIges, "M");
  ASSERT_FALSE(b.surface.IsNull());
  const ReadBack mm = read_back(dir + "/wing.igs", Format::kIges, "MM");
  ASSERT_FALSE(mm.surface.IsNull());
  EXPECT_LE(max_relative_deviation(s, mm.surface, cases[1]->diagonal, 1000.0), 1e-8);
  EXPECT_LE(max_relative_deviation(s, b.surface, cases[1]->diagonal), 1e-8);
}

TEST(CadWriters, RefuseUnknownUnitsAndUnwritablePaths) {
  const auto& s = test::must_pass_cases()[0]->fit.surface;
  const std::string dir = test::temp_dir();
  try {
    write_step(dir + "/x.step", s, CadOptions{.units = "furlong"});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kUsage);
    EXPECT_EQ(e.place().option, "--units");
    EXPECT_NE(std::string(e.what()).find("furlong"), std::string::npos);
  }
  try {
    write_iges(dir + "/missing/x.igs", s);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kOutputWrite);
  }
  // An existing file survives a failed write.
  test::write_file(dir + "/keep.step", "old");
  EXPECT_THROW(write_step(dir + "/keep.step", s, CadOptions{.units = "parsec"}), Error);
  EXPECT_EQ(test::read_file(dir + "/keep.step"), "old");
}

}  // namespace
}  // namespace sfit::exchange
