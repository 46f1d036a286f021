// Writes the seed corpus of fuzz_section_reader: small STEP and IGES files of section curves
// (open and closed B-spline curves, a metre file, a trimmed curve, a polyline), each prefixed
// with the target's format byte (the files: tests/support/section_files.h, shared with the
// section reader's tests). Usage: make_section_seeds FOLDER
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "section_files.h"

namespace {

using sfit::test::section_curves;
using sfit::test::section_edges;

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
  const std::string tmp = dir + "/" + name + ".step";
  sfit::test::write_section_step(tmp, shape, unit);
  seal(tmp, dir + "/" + name, '\0');
}

void iges(const std::string& dir, const std::string& name,
          const std::vector<Handle(Geom_Curve)>& curves, const char* unit) {
  const std::string tmp = dir + "/" + name + ".igs";
  sfit::test::write_section_iges(tmp, curves, unit);
  seal(tmp, dir + "/" + name, '\1');
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_section_seeds FOLDER\n");
    return 2;
  }
  const std::string dir = argv[1];
  const auto open = section_curves(1, false, false), closed = section_curves(1, true, false);
  const auto trimmed = section_curves(1, false, true), big = section_curves(12000, false, false);
  step(dir, "open-step", section_edges(open), "MM");
  step(dir, "closed-step", section_edges(closed), "MM");
  step(dir, "trimmed-step", section_edges(trimmed), "MM");
  step(dir, "metre-step", section_edges(big), "M");
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
