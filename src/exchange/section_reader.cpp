#include <sys/stat.h>
#include <BRepAdaptor_Curve.hxx>
#include <BRepBndLib.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GCPnts_QuasiUniformAbscissa.hxx>
#include <GCPnts_QuasiUniformDeflection.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <Interface_InterfaceModel.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Wire.hxx>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "occt_common.h"
#include "sfit/error.h"
#include "sfit/exchange/readers.h"
#include "sfit/io/file_names.h"

namespace sfit::exchange {

namespace {

bool is_step(const std::string& e) {
  return e == "step" || e == "stp";
}
bool is_iges(const std::string& e) {
  return e == "igs" || e == "iges";
}

[[noreturn]] void fail(ErrorCode code, const std::string& path, const std::string& msg,
                       long row = -1) {
  throw Error(code, msg, Place{.file = path, .row = row});
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
  if (d.IsDone()) n = std::max(n, d.NbPoints());
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

}  // namespace

bool is_exchange_input(const std::string& path) {
  const std::string e = io::extension_of(path);
  return is_step(e) || is_iges(e);
}

SectionsFile read_sections(const std::string& path) {
  const std::string ext = io::extension_of(path);
  if (!is_step(ext) && !is_iges(ext))
    fail(ErrorCode::kUsage, path, "not a STEP (.step, .stp) or IGES (.igs, .iges) file name");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    fail(ErrorCode::kInputUnreadable, path,
         std::string("cannot open input: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode))
    fail(ErrorCode::kInputUnreadable, path, "cannot read input: it is a directory");
  if (!std::ifstream(path, std::ios::binary))
    fail(ErrorCode::kInputUnreadable, path,
         std::string("cannot open input: ") + std::strerror(errno));
  if (st.st_size == 0) fail(ErrorCode::kInputSyntax, path, "empty file: not a STEP or IGES file");

  detail::quiet_occt();
  SectionsFile out;
  out.name = path;
  try {
    TopoDS_Shape shape;
    if (is_step(ext)) {
      STEPControl_Controller::Init();
      STEPControl_Reader reader;
      if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
        fail(ErrorCode::kInputSyntax, path, "not a STEP file OpenCASCADE can read");
      reader.TransferRoots();
      shape = reader.OneShape();
    } else {
      IGESControl_Controller::Init();
      IGESControl_Reader reader;
      if (reader.ReadFile(path.c_str()) != IFSelect_RetDone || reader.Model().IsNull() ||
          reader.Model()->NbEntities() == 0)
        fail(ErrorCode::kInputSyntax, path, "not an IGES file OpenCASCADE can read");
      reader.TransferRoots();
      shape = reader.OneShape();
    }
    if (shape.IsNull())
      fail(ErrorCode::kInputData, path, "the file holds no geometry OpenCASCADE can transfer");
    Bnd_Box box;
    BRepBndLib::Add(shape, box);
    if (box.IsVoid())
      fail(ErrorCode::kInputData, path, "no section curves: the file holds no edges or curves");
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    const double diagonal = Point(x1 - x0, y1 - y0, z1 - z0).norm();
    const double deflection = std::max(kSectionDeflection * diagonal, 1e-12);
    const double same = 1e-9 * diagonal + 1e-15;

    auto add_row = [&](std::vector<Point>& pts) {
      if (pts.size() >= 3 && (pts.front() - pts.back()).norm() <= 1e-7 * diagonal)
        pts.pop_back();  // a closed curve: the first point is not repeated (.rows convention)
      if (pts.empty()) return;
      out.rows.add_row(pts);
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
    if (out.rows.empty()) {
      long faces = 0;
      for (TopExp_Explorer f(shape, TopAbs_FACE); f.More(); f.Next()) ++faces;
      fail(ErrorCode::kInputData, path,
           "no section curves: the file holds " +
               (faces ? std::to_string(faces) + " face(s) and no free curves or wires"
                      : std::string("no curves")));
    }
    for (std::size_t j = 0; j < out.rows.size(); ++j)
      for (const Point& p : out.rows[j])
        if (!p.allFinite())
          fail(ErrorCode::kInputData, path, "curve gives a non-finite point", static_cast<long>(j));
  } catch (const Standard_Failure& f) {
    fail(ErrorCode::kInputSyntax, path,
         "OpenCASCADE failed reading the file (" + detail::describe(f) + ")");
  }
  return out;
}

}  // namespace sfit::exchange
