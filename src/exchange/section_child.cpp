#include "section_child.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <GCPnts_QuasiUniformAbscissa.hxx>
#include <GCPnts_QuasiUniformDeflection.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESData_IGESEntity.hxx>
#include <IGESData_IGESModel.hxx>
#include <Interface_InterfaceModel.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <StepData_StepModel.hxx>
#include <StepShape_GeometricCurveSet.hxx>
#include <StepShape_GeometricSetSelect.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Wire.hxx>
#include <TransferBRep.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>
#include <cctype>
#include <cmath>
#include <optional>

#include "occt_common.h"
#include "sfit/error.h"
#include "sfit/io/file_names.h"

namespace sfit::exchange::detail {

namespace {

[[noreturn]] void fail(ErrorCode code, const std::string& path, const std::string& msg,
                       long row = -1) {
  throw Error(code, msg, Place{.file = path, .row = row});
}

std::string g(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

// IGES curve entity types (the ones sfit can take as a section).
bool is_iges_curve(int type) {
  return type == 100 || type == 102 || type == 104 || type == 106 || type == 110 || type == 112 ||
         type == 126 || type == 130;
}

// Samples one edge in its orientation; appends to `out` (skipping a first sample equal to
// the last one already there, where edges of a wire meet).
void sample_edge(const TopoDS_Edge& edge, double deflection, double same, std::vector<Point>& out) {
  if (BRep_Tool::Degenerated(edge)) return;
  BRepAdaptor_Curve c(edge);
  std::vector<Point> pts;
  // As many samples as the deflection needs, spread uniformly in arc length (points bunched
  // where the curve bends would make the fit's chord-length parameters uneven).
  int n = kMinSectionSamples;
  GCPnts_QuasiUniformDeflection d(c, deflection);
  if (d.IsDone()) n = std::max(n, std::min(d.NbPoints(), 1 << 20));
  GCPnts_QuasiUniformAbscissa a(c, n);
  if (!a.IsDone()) return;
  for (int k = 1; k <= a.NbPoints(); ++k) {
    const gp_Pnt p = c.Value(a.Parameter(k));
    pts.emplace_back(p.X(), p.Y(), p.Z());
  }
  if (edge.Orientation() == TopAbs_REVERSED) std::reverse(pts.begin(), pts.end());
  for (const Point& p : pts)
    if (out.empty() || (out.back() - p).norm() > same) out.push_back(p);
}

// A rough box of the curves themselves (not of their control points: one far pole must not
// make every section look like a point): a few samples per edge in parameter.
double curves_diagonal(const TopoDS_Shape& shape, const std::string& path) {
  Point lo = Point::Constant(INFINITY), hi = Point::Constant(-INFINITY);
  for (TopExp_Explorer e(shape, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    if (BRep_Tool::Degenerated(edge)) continue;
    BRepAdaptor_Curve c(edge);
    const double a = c.FirstParameter(), b = c.LastParameter();
    if (!std::isfinite(a) || !std::isfinite(b)) continue;
    for (int k = 0; k <= 16; ++k) {
      const gp_Pnt p = c.Value(a + (b - a) * k / 16.0);
      const Point q(p.X(), p.Y(), p.Z());
      if (!q.allFinite()) continue;
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  }
  if (!(hi.array() >= lo.array()).all()) return 0.0;
  const double largest = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  if (largest > 1e150) {
    const Point& p = lo.cwiseAbs().maxCoeff() >= hi.cwiseAbs().maxCoeff() ? lo : hi;
    throw Error(ErrorCode::kInputData,
                "a curve reaches " + g(largest) + " (box corner (" + g(p.x()) + ", " + g(p.y()) +
                    ", " + g(p.z()) + ")), out of the range sfit computes in (|x| <= 1e150)",
                Place{.file = path}, {largest});
  }
  return (hi - lo).norm();
}

// A file whose shape gave no section curves: says what it holds instead.
[[noreturn]] void fail_no_sections(const TopoDS_Shape& shape, const std::string& path) {
  long faces = 0;
  for (TopExp_Explorer f(shape, TopAbs_FACE); f.More(); f.Next()) ++faces;
  fail(ErrorCode::kInputData, path,
       "no section curves: the file holds " +
           (faces ? std::to_string(faces) + " face(s) and no free curves or wires"
                  : std::string("no curves")));
}

// Every curve of a geometric curve set (STEP) must have become a shape.
void check_step_curves(STEPControl_Reader& reader, const std::string& path) {
  const Handle(StepData_StepModel) model = Handle(StepData_StepModel)::DownCast(reader.Model());
  const Handle(Transfer_TransientProcess) tp = reader.WS()->TransferReader()->TransientProcess();
  if (model.IsNull() || tp.IsNull()) return;
  for (int i = 1; i <= model->NbEntities(); ++i) {
    const Handle(StepShape_GeometricCurveSet) set =
        Handle(StepShape_GeometricCurveSet)::DownCast(model->Value(i));
    if (set.IsNull() || set->Elements().IsNull()) continue;
    for (int k = 1; k <= set->NbElements(); ++k) {
      const Handle(Standard_Transient) ent = set->ElementsValue(k).Value();
      if (ent.IsNull())
        fail(ErrorCode::kInputData, path,
             "GEOMETRIC_CURVE_SET #" + std::to_string(model->IdentLabel(set)) + " element " +
                 std::to_string(k) + " refers to no entity");
      if (TransferBRep::ShapeResult(tp, ent).IsNull())
        fail(ErrorCode::kInputData, path,
             "entity #" + std::to_string(model->IdentLabel(ent)) + " (" +
                 model->TypeName(ent, Standard_False) + ") of GEOMETRIC_CURVE_SET #" +
                 std::to_string(model->IdentLabel(set)) +
                 " does not translate to a curve: refusing to fit the other sections without it");
    }
  }
}

// Every independent curve entity (IGES) must have become a shape.
void check_iges_curves(IGESControl_Reader& reader, const std::string& path) {
  const Handle(IGESData_IGESModel) model = Handle(IGESData_IGESModel)::DownCast(reader.Model());
  const Handle(Transfer_TransientProcess) tp = reader.WS()->TransferReader()->TransientProcess();
  if (model.IsNull() || tp.IsNull()) return;
  for (int i = 1; i <= reader.NbRootsForTransfer(); ++i) {
    const Handle(IGESData_IGESEntity) ent =
        Handle(IGESData_IGESEntity)::DownCast(reader.RootForTransfer(i));
    if (ent.IsNull() || !is_iges_curve(ent->TypeNumber())) continue;
    if (TransferBRep::ShapeResult(tp, ent).IsNull())
      fail(ErrorCode::kInputData, path,
           "IGES entity " + std::to_string(ent->TypeNumber()) + " at directory line " +
               std::to_string(2 * model->Number(ent) - 1) +
               " does not translate to a curve: refusing to fit the other sections without it");
  }
}

}  // namespace

SectionsFile read_sections_here(const std::string& path) {
  const std::string ext = io::extension_of(path);
  quiet_occt();
  SectionsFile out;
  out.name = path;
  try {
    TopoDS_Shape shape;
    const Unit* unit = nullptr;
    std::string unit_note;
    if (is_step_extension(ext)) {
      STEPControl_Controller::Init();
      STEPControl_Reader reader;
      if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
        fail(ErrorCode::kInputSyntax, path, "not a STEP file OpenCASCADE can read");
      TColStd_SequenceOfAsciiString lengths, angles, solid;
      reader.FileUnits(lengths, angles, solid);
      if (lengths.Length() > 0) unit = step_unit(lengths.First().ToCString());
      if (lengths.Length() > 0 && !unit) unit_note = lengths.First().ToCString();
      if (!unit && lengths.Length() == 0) unit = unit_named("mm");
      for (int k = 2; unit && k <= lengths.Length(); ++k)
        if (step_unit(lengths.Value(k).ToCString()) != unit)
          fail(ErrorCode::kInputData, path,
               std::string("the file mixes length units (") + lengths.First().ToCString() + ", " +
                   lengths.Value(k).ToCString() + "): give its sections in one unit");
      const Unit& u = unit ? *unit : *unit_named("mm");
      const SessionUnit session(u);
      reader.SetSystemLengthUnit(u.mm);
      reader.TransferRoots();
      check_step_curves(reader, path);
      shape = reader.OneShape();
    } else {
      IGESControl_Controller::Init();
      IGESControl_Reader reader;
      if (reader.ReadFile(path.c_str()) != IFSelect_RetDone || reader.Model().IsNull() ||
          reader.Model()->NbEntities() == 0)
        fail(ErrorCode::kInputSyntax, path, "not an IGES file OpenCASCADE can read");
      const Handle(IGESData_IGESModel) model = Handle(IGESData_IGESModel)::DownCast(reader.Model());
      const int flag = model.IsNull() ? 2 : model->GlobalSection().UnitFlag();
      unit = iges_unit(flag);
      if (!unit) unit_note = "IGES unit flag " + std::to_string(flag);
      const Unit& u = unit ? *unit : *unit_named("mm");
      const SessionUnit session(u);
      if (!model.IsNull()) model->ChangeGlobalSection().SetCascadeUnit(u.mm);
      reader.TransferRoots();
      check_iges_curves(reader, path);
      shape = reader.OneShape();
    }
    // Coordinates are in the file's unit; a unit sfit has no name for is converted to mm.
    out.units = unit ? unit->ours : "mm (converted from " + unit_note + ")";
    if (shape.IsNull())
      fail(ErrorCode::kInputData, path, "the file holds no geometry OpenCASCADE can transfer");
    const double diagonal = curves_diagonal(shape, path);
    if (!(diagonal > 0) || !std::isfinite(diagonal)) {
      bool any_edge = false;
      for (TopExp_Explorer e(shape, TopAbs_EDGE); e.More() && !any_edge; e.Next()) any_edge = true;
      if (!any_edge) fail_no_sections(shape, path);
      fail(ErrorCode::kInputData, path,
           std::isfinite(diagonal) ? "the curves span no length: every one is a single point"
                                   : "the curves reach infinity");
    }
    const double deflection = std::max(kSectionDeflection * diagonal, 1e-300);
    const double same = 1e-9 * diagonal;

    auto add_row = [&](std::vector<Point>& pts) {
      bool closed = false;
      if (pts.size() >= 3 && (pts.front() - pts.back()).norm() <= 1e-7 * diagonal) {
        pts.pop_back();  // a closed curve: the first point is not repeated (.rows convention)
        closed = true;
      }
      if (pts.empty()) return;
      out.rows.add_row(pts);
      out.closed.push_back(closed);
    };
    // Wires outside faces: one row each, edges in wire order.
    for (TopExp_Explorer w(shape, TopAbs_WIRE, TopAbs_FACE); w.More(); w.Next()) {
      std::vector<Point> pts;
      for (BRepTools_WireExplorer e(TopoDS::Wire(w.Current())); e.More(); e.Next())
        sample_edge(e.Current(), deflection, same, pts);
      add_row(pts);
    }
    // Free edges (in no wire): one row each.
    for (TopExp_Explorer e(shape, TopAbs_EDGE, TopAbs_WIRE); e.More(); e.Next()) {
      std::vector<Point> pts;
      sample_edge(TopoDS::Edge(e.Current()), deflection, same, pts);
      add_row(pts);
    }
    if (out.rows.empty()) fail_no_sections(shape, path);
  } catch (const Standard_Failure& f) {
    fail(ErrorCode::kInputSyntax, path,
         "OpenCASCADE failed reading the file (" + describe(f) + ")");
  }
  return out;
}

}  // namespace sfit::exchange::detail
