// Reads a STEP file the editor exported with OpenCASCADE's own reader and compares its
// B-spline face with the editor's surface JSON (exported beside it) on a 50 x 50 grid.
// Prints one JSON line; exit 0 when it could compare, 1 otherwise. Used by
// editor/tests/browser_test.mjs.
#include <BRepCheck_Analyzer.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <cstdio>

#include "sfit/io/surface_json.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: step_readback FILE.step SURFACE.json\n");
    return 1;
  }
  const sfit::Surface s = sfit::io::read_surface_json(argv[2]);
  STEPControl_Reader reader;
  if (reader.ReadFile(argv[1]) != IFSelect_RetDone) {
    std::printf("{\"error\": \"OpenCASCADE cannot read %s\"}\n", argv[1]);
    return 1;
  }
  reader.TransferRoots();
  const TopoDS_Shape shape = reader.OneShape();
  int faces = 0;
  Handle(Geom_BSplineSurface) g;
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
    ++faces;
    g = Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(TopoDS::Face(e.Current())));
  }
  if (g.IsNull()) {
    std::printf("{\"faces\": %d, \"error\": \"no B-spline face\"}\n", faces);
    return 1;
  }
  sfit::Point lo = s.control[0], hi = s.control[0];
  for (const auto& p : s.control) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diagonal = std::max((hi - lo).norm(), 1e-300);
  double worst = 0;
  for (int a = 0; a < 50; ++a)
    for (int b = 0; b < 50; ++b) {
      const double u = s.u_end() * a / 49, v = s.v_end() * b / 49;
      const gp_Pnt q = g->Value(u, v);
      worst =
          std::max(worst, (s.evaluate(u, v) - sfit::Point(q.X(), q.Y(), q.Z())).norm() / diagonal);
    }
  std::printf(
      "{\"faces\": %d, \"valid\": %s, \"degree\": [%d, %d], \"poles\": [%d, %d], "
      "\"control_points\": [%d, %d], \"max_relative_deviation\": %.17g}\n",
      faces, BRepCheck_Analyzer(shape).IsValid() ? "true" : "false", g->UDegree(), g->VDegree(),
      g->NbUPoles(), g->NbVPoles(), s.count_u, s.count_v, worst);
  return 0;
}
