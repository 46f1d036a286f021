// OpenCASCADE's fitters: GeomAPI_PointsToBSplineSurface for grids, and the lofting path
// (GeomAPI_PointsToBSpline per row, then GeomFill_AppSurf) for ragged rows.
#include <BSplCLib.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <GeomFill_AppSurf.hxx>
#include <GeomFill_Line.hxx>
#include <GeomFill_SectionGenerator.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <stdexcept>
#include <vector>

#include "peers.h"

namespace sfit::peers {

namespace {

std::string failure_text(const Standard_Failure& f) {
  const char* msg = f.GetMessageString();
  return std::string(f.DynamicType()->Name()) + (msg && *msg ? std::string(": ") + msg : "");
}

std::string shape_of(const Handle(Geom_BSplineSurface) & s) {
  return std::to_string(s->NbUPoles()) + "x" + std::to_string(s->NbVPoles());
}

class OcctGrid final : public Peer {
 public:
  OcctGrid(const Rows& rows, double t) : points_(1, rows[0].size(), 1, rows.size()), tol_(t) {
    for (std::size_t j = 0; j < rows.size(); ++j)
      for (std::size_t i = 0; i < rows[j].size(); ++i) {
        const Point& p = rows[j][i];
        points_(i + 1, j + 1) = gp_Pnt(p.x(), p.y(), p.z());
      }
  }
  void fit() override {
    try {
      GeomAPI_PointsToBSplineSurface fitter;
      fitter.Init(points_, 3, 3, GeomAbs_C2, tol_);
      if (!fitter.IsDone()) throw std::runtime_error("GeomAPI_PointsToBSplineSurface: not done");
      surface_ = fitter.Surface();
    } catch (const Standard_Failure& f) {
      throw std::runtime_error(failure_text(f));
    }
  }
  Handle(Geom_BSplineSurface) surface() const override { return surface_; }
  long coefficients() const override {
    return static_cast<long>(surface_->NbUPoles()) * surface_->NbVPoles();
  }
  std::string shape() const override { return shape_of(surface_); }

 private:
  TColgp_Array2OfPnt points_;
  double tol_;
  Handle(Geom_BSplineSurface) surface_;
};

class OcctLoft final : public Peer {
 public:
  OcctLoft(const Rows& rows, double t, bool closed_u) : tol_(t) {
    for (std::size_t j = 0; j < rows.size(); ++j) {
      const auto row = rows[j];
      const int n = static_cast<int>(row.size()) + (closed_u ? 1 : 0);
      TColgp_Array1OfPnt a(1, n);
      for (int i = 0; i < n; ++i) {
        const Point& p = row[static_cast<std::size_t>(i) % row.size()];
        a(i + 1) = gp_Pnt(p.x(), p.y(), p.z());
      }
      rows_.push_back(a);
    }
  }
  void fit() override {
    try {
      GeomFill_SectionGenerator sections;
      for (const TColgp_Array1OfPnt& row : rows_) {
        GeomAPI_PointsToBSpline curve_fit(row, 3, 3, GeomAbs_C2, 0.5 * tol_);
        if (!curve_fit.IsDone()) throw std::runtime_error("GeomAPI_PointsToBSpline: not done");
        Handle(Geom_BSplineCurve) c = curve_fit.Curve();
        // As BRepOffsetAPI_ThruSections does: every section on [0, 1].
        TColStd_Array1OfReal k(1, c->NbKnots());
        c->Knots(k);
        BSplCLib::Reparametrize(0., 1., k);
        c->SetKnots(k);
        sections.AddCurve(c);
      }
      sections.Perform(Precision::PConfusion());
      Handle(GeomFill_Line) line = new GeomFill_Line(static_cast<int>(rows_.size()));
      // ThruSections' choice of iterations for its tolerance.
      const int iterations = 0.5 * tol_ <= 1e-3 ? 0 : 3;
      GeomFill_AppSurf app(3, 3, 0.5 * tol_, 0.5 * tol_, iterations);
      app.SetContinuity(GeomAbs_C2);
      app.Perform(line, sections, Standard_True);
      if (!app.IsDone()) throw std::runtime_error("GeomFill_AppSurf: not done");
      surface_ = new Geom_BSplineSurface(app.SurfPoles(), app.SurfWeights(), app.SurfUKnots(),
                                         app.SurfVKnots(), app.SurfUMults(), app.SurfVMults(),
                                         app.UDegree(), app.VDegree());
    } catch (const Standard_Failure& f) {
      throw std::runtime_error(failure_text(f));
    }
  }
  Handle(Geom_BSplineSurface) surface() const override { return surface_; }
  long coefficients() const override {
    return static_cast<long>(surface_->NbUPoles()) * surface_->NbVPoles();
  }
  std::string shape() const override { return shape_of(surface_); }
  std::string notes() const override {
    return "degree " + std::to_string(surface_->UDegree()) + "x" +
           std::to_string(surface_->VDegree());
  }

 private:
  std::vector<TColgp_Array1OfPnt> rows_;
  double tol_;
  Handle(Geom_BSplineSurface) surface_;
};

}  // namespace

std::unique_ptr<Peer> make_occt_grid(const Rows& rows, double t) {
  return std::make_unique<OcctGrid>(rows, t);
}

std::unique_ptr<Peer> make_occt_loft(const Rows& rows, double t, bool closed_u) {
  return std::make_unique<OcctLoft>(rows, t, closed_u);
}

}  // namespace sfit::peers
