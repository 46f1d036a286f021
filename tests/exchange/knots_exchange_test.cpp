// Non-uniform knots (with multiplicities) through STEP and IGES: written by sfit, read back by
// OpenCASCADE's own readers (the knots and multiplicities as written, the surface evaluating
// like ours) and by sfit's reader (the same KnotVector); and the meshes of such a surface.
#include <gtest/gtest.h>
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <cmath>
#include <random>

#include "sfit/exchange/cad_writers.h"
#include "sfit/exchange/surface_reader.h"
#include "sfit/knot_vector.h"
#include "test_support.h"

namespace sfit::exchange {
namespace {

// A wavy sheet (open u with a 3-fold knot: a crease) or a tube (periodic u with a double knot).
Surface sample(bool periodic_u) {
  Surface s;
  s.degree_u = 3;
  s.degree_v = 2;
  s.periodic_u = periodic_u;
  const double bu[] = {0, 0.4, 0.5, 1.7, 2.0, 3.1};
  const int mu_open[] = {1, 3, 1, 2}, mu_closed[] = {1, 1, 2, 1, 1};
  const KnotVector ku = periodic_u ? KnotVector::from_breaks(3, true, bu, mu_closed)
                                   : KnotVector::from_breaks(3, false, bu, mu_open);
  const double bv[] = {0, 0.25, 1.5, 2};
  const int mv[] = {2, 1};
  const KnotVector kv = KnotVector::from_breaks(2, false, bv, mv);
  s.count_u = ku.count();
  s.count_v = kv.count();
  s.set_knots_u(ku);
  s.set_knots_v(kv);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> r(-0.2, 0.2);
  for (int i = 0; i < s.count_u; ++i)
    for (int j = 0; j < s.count_v; ++j) {
      const double a = 2 * M_PI * i / s.count_u;
      s.control.push_back(periodic_u ? Point(10 * std::cos(a), 10 * std::sin(a), 3.0 * j)
                                     : Point(2.0 * i, 3.0 * j, r(rng) + (i == 4 ? 2 : 0)));
    }
  return s;
}

Handle(Geom_BSplineSurface) occt_read(const std::string& path, bool step) {
  TopoDS_Shape shape;
  if (step) {
    STEPControl_Controller::Init();
    STEPControl_Reader r;
    EXPECT_EQ(r.ReadFile(path.c_str()), IFSelect_RetDone);
    r.TransferRoots();
    shape = r.OneShape();
  } else {
    IGESControl_Controller::Init();
    IGESControl_Reader r;
    EXPECT_EQ(r.ReadFile(path.c_str()), IFSelect_RetDone);
    r.TransferRoots();
    shape = r.OneShape();
  }
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next())
    return Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(TopoDS::Face(e.Current())));
  return {};
}

void expect_knots(const KnotVector& k, const TColStd_Array1OfReal& knots,
                  const TColStd_Array1OfInteger& mults) {
  std::vector<double> values;
  std::vector<int> m;
  k.breaks(values, m);
  ASSERT_EQ(knots.Length(), static_cast<int>(values.size()));
  for (int i = 0; i < knots.Length(); ++i) {
    EXPECT_NEAR(knots(knots.Lower() + i), values[i], 1e-12) << i;
    EXPECT_EQ(mults(mults.Lower() + i), m[i]) << i;
  }
}

class KnotsExchange : public ::testing::TestWithParam<bool> {};

TEST_P(KnotsExchange, StepAndIgesKeepNonUniformKnots) {
  const Surface s = sample(GetParam());
  ASSERT_FALSE(s.knots_u.uniform());
  const std::string dir = test::temp_dir();
  for (const bool step : {true, false}) {
    SCOPED_TRACE(step ? "STEP" : "IGES");
    const std::string path = dir + (step ? "/nu.step" : "/nu.igs");
    if (step)
      write_step(path, s);
    else
      write_iges(path, s);
    const Handle(Geom_BSplineSurface) g = occt_read(path, step);
    ASSERT_FALSE(g.IsNull());
    EXPECT_EQ(g->IsUPeriodic(), s.periodic_u);
    EXPECT_EQ(g->NbUPoles(), s.count_u);
    EXPECT_EQ(g->NbVPoles(), s.count_v);
    expect_knots(s.knots_u, g->UKnots(), g->UMultiplicities());
    expect_knots(s.knots_v, g->VKnots(), g->VMultiplicities());
    double worst = 0;
    for (int a = 0; a <= 60; ++a)
      for (int b = 0; b <= 60; ++b) {
        const double u = s.u_end() * a / 60, v = s.v_end() * b / 60;
        const gp_Pnt q = g->Value(u, v);
        worst = std::max(worst, (s.evaluate(u, v) - Point(q.X(), q.Y(), q.Z())).norm());
      }
    EXPECT_LE(worst, 1e-9);
    // sfit's own reader gives the same knots back.
    const Surface t = read_cad_surface(path);
    ASSERT_FALSE(t.knots_u.uniform());
    ASSERT_EQ(t.full_knots_u().size(), s.full_knots_u().size());
    for (std::size_t i = 0; i < t.full_knots_u().size(); ++i)
      EXPECT_NEAR(t.full_knots_u()[i], s.full_knots_u()[i], 1e-12);
    EXPECT_LE((t.evaluate(1.1, 0.3) - s.evaluate(1.1, 0.3)).norm(), 1e-9);
  }
}

INSTANTIATE_TEST_SUITE_P(OpenAndPeriodic, KnotsExchange, ::testing::Values(false, true));

}  // namespace
}  // namespace sfit::exchange
