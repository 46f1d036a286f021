// Small STEP and IGES files of section curves (section_files.h).
#include "section_files.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRep_Builder.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopoDS_Edge.hxx>

#include <cmath>

namespace sfit::test {

std::vector<Handle(Geom_Curve)> section_curves(double scale, bool closed, bool trimmed) {
  std::vector<Handle(Geom_Curve)> out;
  for (int j = 0; j < 3; ++j) {
    const int n = 6;
    Handle(TColgp_HArray1OfPnt) pts = new TColgp_HArray1OfPnt(1, n);
    for (int k = 0; k < n; ++k) {
      const double t = closed ? 2 * M_PI * k / n : k / (n - 1.0);
      pts->SetValue(k + 1, closed
                               ? gp_Pnt(scale * std::cos(t), scale * std::sin(t), scale * j)
                               : gp_Pnt(scale * t, scale * j, scale * 0.2 * std::sin(3 * t + j)));
    }
    GeomAPI_Interpolate in(pts, closed, 1e-9);
    in.Perform();
    Handle(Geom_Curve) c = Handle(Geom_BSplineCurve)(in.Curve());
    if (trimmed) c = new Geom_TrimmedCurve(c, c->FirstParameter() + 0.1, c->LastParameter() - 0.1);
    out.push_back(c);
  }
  return out;
}

TopoDS_Compound section_edges(const std::vector<Handle(Geom_Curve)>& curves) {
  BRep_Builder b;
  TopoDS_Compound c;
  b.MakeCompound(c);
  for (const auto& k : curves) b.Add(c, BRepBuilderAPI_MakeEdge(k).Edge());
  return c;
}

bool write_section_step(const std::string& path, const TopoDS_Shape& shape, const char* unit) {
  STEPControl_Controller::Init();
  Interface_Static::SetCVal("write.step.unit", unit);
  STEPControl_Writer w;
  const bool transferred = w.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone;
  const bool written = w.Write(path.c_str()) == IFSelect_RetDone;
  Interface_Static::SetCVal("write.step.unit", "MM");
  return transferred && written;
}

bool write_section_iges(const std::string& path, const std::vector<Handle(Geom_Curve)>& curves,
                        const char* unit) {
  IGESControl_Controller::Init();
  IGESControl_Writer w(unit, 0);
  bool added = true;
  for (const auto& c : curves) added = w.AddGeom(c) && added;
  w.ComputeModel();
  return w.Write(path.c_str()) && added;
}

}  // namespace sfit::test
