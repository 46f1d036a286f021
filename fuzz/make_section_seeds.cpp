// Writes the seed corpus of fuzz_section_reader: small STEP and IGES files of section curves
// (open and closed B-spline curves, a metre file, a trimmed curve, a polyline), each prefixed
// with the target's format byte. Usage: make_section_seeds FOLDER
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
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
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::vector<Handle(Geom_Curve)> sections(double scale, bool closed, bool trimmed) {
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

// Prefixes the file with the fuzz target's format byte (0: STEP, 1: IGES).
void seal(const std::string& tmp, const std::string& out, char format) {
  std::ifstream in(tmp, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  std::ofstream(out, std::ios::binary) << format << s.str();
  std::remove(tmp.c_str());
}

void step(const std::string& dir, const std::string& name, const TopoDS_Shape& shape,
          const char* unit) {
  STEPControl_Controller::Init();
  Interface_Static::SetCVal("write.step.unit", unit);
  STEPControl_Writer w;
  w.Transfer(shape, STEPControl_AsIs);
  const std::string tmp = dir + "/" + name + ".step";
  w.Write(tmp.c_str());
  seal(tmp, dir + "/" + name, '\0');
}

void iges(const std::string& dir, const std::string& name,
          const std::vector<Handle(Geom_Curve)>& curves, const char* unit) {
  IGESControl_Controller::Init();
  IGESControl_Writer w(unit, 0);
  for (const auto& c : curves) w.AddGeom(c);
  w.ComputeModel();
  const std::string tmp = dir + "/" + name + ".igs";
  w.Write(tmp.c_str());
  seal(tmp, dir + "/" + name, '\1');
}

TopoDS_Compound edges(const std::vector<Handle(Geom_Curve)>& curves) {
  BRep_Builder b;
  TopoDS_Compound c;
  b.MakeCompound(c);
  for (const auto& k : curves) b.Add(c, BRepBuilderAPI_MakeEdge(k).Edge());
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_section_seeds FOLDER\n");
    return 2;
  }
  const std::string dir = argv[1];
  const auto open = sections(1, false, false), closed = sections(1, true, false);
  const auto trimmed = sections(1, false, true), big = sections(12000, false, false);
  step(dir, "open-step", edges(open), "MM");
  step(dir, "closed-step", edges(closed), "MM");
  step(dir, "trimmed-step", edges(trimmed), "MM");
  step(dir, "metre-step", edges(big), "M");
  iges(dir, "open-iges", open, "MM");
  iges(dir, "closed-iges", closed, "MM");
  iges(dir, "trimmed-iges", trimmed, "MM");
  iges(dir, "metre-iges", big, "M");
  BRepBuilderAPI_MakePolygon poly(gp_Pnt(0, 0, 0), gp_Pnt(1, 0, 0), gp_Pnt(1, 1, 0),
                                  gp_Pnt(0, 1, 0.5));
  BRep_Builder b;
  TopoDS_Compound c;
  b.MakeCompound(c);
  b.Add(c, poly.Wire());
  b.Add(c, BRepBuilderAPI_MakePolygon(gp_Pnt(0, 0, 1), gp_Pnt(1, 0, 1), gp_Pnt(1, 1, 1)).Wire());
  step(dir, "wires-step", c, "MM");
  std::printf("make_section_seeds: 9 seeds in %s\n", dir.c_str());
  return 0;
}
