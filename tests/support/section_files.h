// Small STEP and IGES files of section curves (open and closed B-spline curves, trimmed ones,
// in mm or m), written through OpenCASCADE: the section reader's tests
// (tests/exchange/section_isolation_test.cpp, section_reader_test.cpp) and the fuzz seed corpus
// (fuzz/make_section_seeds.cpp) build the same files from here. Needs OpenCASCADE's
// TKGeomAlgo, TKTopAlgo, TKSTEP and TKIGES.
#pragma once

#include <Geom_Curve.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shape.hxx>

#include <string>
#include <vector>

namespace sfit::test {

/// Three section curves through 6 points each (GeomAPI_Interpolate): open ones across x
/// (t in [0, 1], row j at y = j, z a small sine), or closed circles of radius 1 at z = j;
/// every length times `scale` (in the writer's unit). `trimmed`: each trimmed 0.1 in from
/// both ends of its parameter range (Geom_TrimmedCurve).
std::vector<Handle(Geom_Curve)> section_curves(double scale, bool closed, bool trimmed);

/// The curves as the edges of one compound.
TopoDS_Compound section_edges(const std::vector<Handle(Geom_Curve)>& curves);

/// Writes `shape` as a STEP file at `path`, lengths in `unit` ("MM", "M", ...); the session's
/// write.step.unit is MM again afterwards. False where the transfer or the write failed.
bool write_section_step(const std::string& path, const TopoDS_Shape& shape,
                        const char* unit = "MM");

/// Writes `curves` as an IGES file at `path`, lengths in `unit`. False where a curve was not
/// added or the write failed.
bool write_section_iges(const std::string& path, const std::vector<Handle(Geom_Curve)>& curves,
                        const char* unit = "MM");

}  // namespace sfit::test
