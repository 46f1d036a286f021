#include "sfit/exchange/surface_reader.h"

#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESData_IGESModel.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "occt_common.h"
#include "sfit/error.h"
#include "sfit/io/file_names.h"

namespace sfit::exchange {

namespace {

using detail::iges_unit;
using detail::SessionUnit;
using detail::step_unit;
using detail::Unit;
using detail::unit_named;

[[noreturn]] void fail(ErrorCode code, const std::string& path, const std::string& msg) {
  throw Error(code, msg, Place{.file = path});
}

// The knots of one direction: uniform when they are sfit's uniform layout up to an affine map
// (degree + 1 at the ends of an open direction, 1 everywhere in a periodic one, equal steps),
// otherwise the KnotVector of the knots as they are (shifted to begin at 0).
KnotVector read_knots(const std::string& path, const char* dir, int degree, bool periodic,
                      int poles, const TColStd_Array1OfReal& knots,
                      const TColStd_Array1OfInteger& mults) {
  const int n = knots.Length(), lo = knots.Lower();
  bool uniform = n == (periodic ? poles + 1 : poles - degree + 1) && n >= 2;
  for (int k = 0; k < n && uniform; ++k) {
    const bool end = !periodic && (k == 0 || k == n - 1);
    uniform = mults(lo + k) == (end ? degree + 1 : 1);
  }
  if (uniform) {
    const double a = knots(lo), h = (knots(lo + n - 1) - a) / (n - 1);
    for (int k = 0; k < n && uniform; ++k)
      uniform = std::abs(knots(lo + k) - (a + k * h)) <= 1e-9 * std::abs(h) * n;
    if (uniform) return {};
  }
  std::vector<double> breaks;
  std::vector<int> inner;
  for (int k = 0; k < n; ++k) {
    breaks.push_back(knots(lo + k) - knots(lo));
    const int m = mults(lo + k);
    const bool end = k == 0 || k == n - 1;
    if (!periodic && end && m != degree + 1)
      fail(ErrorCode::kInputData, path,
           std::string("the surface's knots along ") + dir + " have end multiplicity " +
               std::to_string(m) + ": sfit reads clamped ends (" + std::to_string(degree + 1) +
               "-fold)");
    if (periodic ? k < n - 1 : !end) inner.push_back(m);
  }
  try {
    KnotVector kv = KnotVector::from_breaks(degree, periodic, breaks, inner);
    if (kv.count() != poles)
      fail(ErrorCode::kInputData, path,
           std::string("the surface's knots along ") + dir + " do not match its poles");
    return kv;
  } catch (const Error& e) {
    if (e.code() != ErrorCode::kInputData || e.place().file == path) throw;
    fail(ErrorCode::kInputData, path,
         std::string("the surface's knots along ") + dir + ": " + e.what());
  }
}

Surface to_surface(const std::string& path, const Handle(Geom_BSplineSurface) & g) {
  if (g->IsURational() || g->IsVRational()) {
    const double w0 = g->Weight(1, 1);
    for (int i = 1; i <= g->NbUPoles(); ++i)
      for (int j = 1; j <= g->NbVPoles(); ++j)
        if (g->Weight(i, j) != w0)
          fail(ErrorCode::kInputData, path,
               "the surface is rational (unequal weights): sfit surfaces are polynomial");
  }
  Surface s;
  s.degree_u = g->UDegree();
  s.degree_v = g->VDegree();
  s.periodic_u = g->IsUPeriodic();
  s.periodic_v = g->IsVPeriodic();
  if (s.degree_u < 1 || s.degree_u > 20 || s.degree_v < 1 || s.degree_v > 20)
    fail(ErrorCode::kInputData, path, "the surface's degrees are outside 1 ... 20");
  s.count_u = g->NbUPoles();
  s.count_v = g->NbVPoles();
  s.set_knots_u(read_knots(path, "u", s.degree_u, s.periodic_u, s.count_u, g->UKnots(),
                           g->UMultiplicities()));
  s.set_knots_v(read_knots(path, "v", s.degree_v, s.periodic_v, s.count_v, g->VKnots(),
                           g->VMultiplicities()));
  s.control.reserve(static_cast<std::size_t>(s.count_u) * s.count_v);
  for (int i = 1; i <= s.count_u; ++i)
    for (int j = 1; j <= s.count_v; ++j) {
      const gp_Pnt p = g->Pole(i, j);
      const Point q(p.X(), p.Y(), p.Z());
      if (!q.allFinite()) fail(ErrorCode::kInputData, path, "a pole is not finite");
      s.control.push_back(q);
    }
  return s;
}

TopoDS_Shape read_shape(const std::string& path) {
  const std::string ext = io::extension_of(path);
  const bool step = ext == "step" || ext == "stp";
  if (!step && ext != "iges" && ext != "igs")
    fail(ErrorCode::kUsage, path, "not a .step, .stp, .iges or .igs file");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || !std::ifstream(path).good())
    fail(ErrorCode::kInputUnreadable, path, "cannot read the file");
  if (step) {
    STEPControl_Controller::Init();
    STEPControl_Reader reader;
    if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
      fail(ErrorCode::kInputSyntax, path, "not a STEP file OpenCASCADE can read");
    TColStd_SequenceOfAsciiString lengths, angles, solid;
    reader.FileUnits(lengths, angles, solid);
    const Unit* unit = lengths.Length() > 0 ? step_unit(lengths.First().ToCString()) : nullptr;
    const Unit& u = unit ? *unit : *unit_named("mm");
    const SessionUnit session(u);
    reader.SetSystemLengthUnit(u.mm);
    reader.TransferRoots();
    return reader.OneShape();
  }
  IGESControl_Controller::Init();
  IGESControl_Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone || reader.Model().IsNull() ||
      reader.Model()->NbEntities() == 0)
    fail(ErrorCode::kInputSyntax, path, "not an IGES file OpenCASCADE can read");
  const Handle(IGESData_IGESModel) model = Handle(IGESData_IGESModel)::DownCast(reader.Model());
  const Unit* unit = iges_unit(model.IsNull() ? 2 : model->GlobalSection().UnitFlag());
  const Unit& u = unit ? *unit : *unit_named("mm");
  const SessionUnit session(u);
  if (!model.IsNull()) model->ChangeGlobalSection().SetCascadeUnit(u.mm);
  reader.TransferRoots();
  return reader.OneShape();
}

}  // namespace

Surface read_cad_surface(const std::string& path) {
  detail::quiet_occt();
  try {
    const TopoDS_Shape shape = read_shape(path);
    int faces = 0;
    Handle(Geom_Surface) surface;
    if (!shape.IsNull())
      for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
        ++faces;
        surface = BRep_Tool::Surface(TopoDS::Face(e.Current()));
      }
    if (faces != 1)
      fail(ErrorCode::kInputData, path,
           "the file has " + std::to_string(faces) + " faces: a surface file has exactly one");
    if (const auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(surface); !t.IsNull())
      surface = t->BasisSurface();
    const auto g = Handle(Geom_BSplineSurface)::DownCast(surface);
    if (g.IsNull())
      fail(ErrorCode::kInputData, path,
           std::string("the face is not on a B-spline surface (") + surface->DynamicType()->Name() +
               ")");
    return to_surface(path, g);
  } catch (const Standard_Failure& f) {
    fail(ErrorCode::kInputUnreadable, path,
         "cannot read the file: OpenCASCADE failed (" + detail::describe(f) + ")");
  }
}

}  // namespace sfit::exchange
