#include "sfit/exchange/cad_writers.h"

#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <Interface_Static.hxx>
#include <Precision.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <StepData_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <UnitsMethods.hxx>
#include <XSControl_WorkSession.hxx>
#include <algorithm>
#include <array>
#include <filesystem>

#include "occt_common.h"
#include "sfit/error.h"
#include "sfit/io/atomic_file.h"
#include "sfit/version.h"

namespace sfit::exchange {

namespace {

using detail::kUnits;
using detail::SessionUnit;
using detail::Unit;

const Unit& find_unit(const std::string& units) {
  if (const Unit* u = detail::unit_named(units)) return *u;
  check_units(units);  // throws
  return kUnits[0];
}

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw Error(ErrorCode::kOutputWrite, "cannot write output: " + why, Place{.file = path});
}

TopoDS_Face make_face(const std::string& path, const Surface& s) {
  if (s.count_u < 1 || s.count_v < 1 ||
      s.control.size() != static_cast<std::size_t>(s.count_u) * s.count_v)
    throw Error(ErrorCode::kInternal, "surface with inconsistent control-point counts",
                Place{.file = path});
  try {
    BRepBuilderAPI_MakeFace mf(detail::to_occt(s), Precision::Confusion());
    if (!mf.IsDone()) fail(path, "OpenCASCADE could not make a face on the surface");
    return mf.Face();
  } catch (const Standard_Failure& f) {
    fail(path, "OpenCASCADE refused the surface (" + detail::describe(f) + ")");
  }
}

std::string product_name(const std::string& path, const CadOptions& o) {
  return o.name.empty() ? std::filesystem::path(path).stem().string() : o.name;
}

}  // namespace

void write_step(const std::string& path, const Surface& s, const CadOptions& o) {
  const Unit& unit = find_unit(o.units);
  io::check_writable(path);
  detail::quiet_occt();
  const TopoDS_Face face = make_face(path, s);
  try {
    STEPControl_Controller::Init();
    const SessionUnit session(unit);
    Interface_Static::SetCVal("write.step.schema", "AP214IS");
    Interface_Static::SetCVal("write.step.unit", unit.occt);
    Interface_Static::SetCVal("write.step.product.name", product_name(path, o).c_str());
    STEPControl_Writer writer;
    if (writer.Transfer(face, STEPControl_AsIs) != IFSelect_RetDone)
      fail(path, "OpenCASCADE could not translate the face to STEP");
    APIHeaderSection_MakeHeader header(writer.Model());
    header.SetName(new TCollection_HAsciiString(product_name(path, o).c_str()));
    header.SetAuthorValue(1, new TCollection_HAsciiString("sfit"));
    header.SetOrganizationValue(1, new TCollection_HAsciiString(""));
    header.SetOriginatingSystem(
        new TCollection_HAsciiString("sfit " SFIT_VERSION_STRING " (OpenCASCADE 7.6)"));
    header.SetDescriptionValue(
        1, new TCollection_HAsciiString("B-spline surface fitted by sfit (Vergeest 1989, SFIT01)"));
    // STEPControl_Writer::Write() prints reals with 13 significant digits (%14.12E), too few
    // for a surface far from the origin (1e2 apart at 1e15): print 17 so the file round-trips
    // our doubles, through the same StepData_StepWriter Write() uses.
    const Handle(StepData_Protocol) protocol =
        Handle(StepData_Protocol)::DownCast(writer.WS()->Protocol());
    if (protocol.IsNull()) fail(path, "OpenCASCADE has no STEP protocol");
    StepData_StepWriter printer(writer.Model());
    printer.FloatWriter().SetFormat("%.16E");
    printer.SendModel(protocol);
    io::write_file_atomically(path, [&](std::ostream& out) {
      if (!printer.Print(out)) fail(path, "OpenCASCADE could not write the STEP file");
    });
  } catch (const Standard_Failure& f) {
    fail(path, "OpenCASCADE failed writing STEP (" + detail::describe(f) + ")");
  }
}

void write_iges(const std::string& path, const Surface& s, const CadOptions& o) {
  const Unit& unit = find_unit(o.units);
  io::check_writable(path);
  detail::quiet_occt();
  const TopoDS_Face face = make_face(path, s);
  try {
    IGESControl_Controller::Init();
    const SessionUnit session(unit);
    Interface_Static::SetCVal("write.iges.unit", unit.occt);
    // Mode 0: faces as trimmed surfaces (144) on their B-spline surface (128), which every
    // IGES reader takes; mode 1 (BRep, 186) is less widely read.
    IGESControl_Writer writer(unit.occt, 0);
    writer.Model()->ChangeGlobalSection().SetCascadeUnit(unit.mm);
    if (!writer.AddShape(face)) fail(path, "OpenCASCADE could not translate the face to IGES");
    writer.ComputeModel();
    // IGESControl_Writer::Write() prints reals with 10 significant digits; print 17 so the
    // file round-trips our doubles.
    IGESData_IGESWriter printer(writer.Model());
    printer.FloatWriter().SetFormat("%.16E");
    printer.SendModel(IGESSelect_WorkLibrary::DefineProtocol());
    io::write_file_atomically(path, [&](std::ostream& out) {
      if (!printer.Print(out)) fail(path, "OpenCASCADE could not write the IGES file");
    });
  } catch (const Standard_Failure& f) {
    fail(path, "OpenCASCADE failed writing IGES (" + detail::describe(f) + ")");
  }
}

}  // namespace sfit::exchange
