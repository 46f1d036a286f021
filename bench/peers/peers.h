// The fitters compared in the peer benchmark, behind one interface so that the harness times
// exactly the fitting call of each and checks every result with the same checker.
#pragma once

#include <Geom_BSplineSurface.hxx>
#include <memory>
#include <string>

#include "sfit/parametrization.h"
#include "sfit/rows.h"

namespace sfit::peers {

/// One tool set up on one data set and tolerance. The constructor converts the rows to the
/// tool's own input (not timed); fit() is the timed call; surface() turns the last result into
/// an OpenCASCADE surface for the common checker (not timed).
class Peer {
 public:
  virtual ~Peer() = default;
  /// Runs the fit; throws std::runtime_error if the tool reports a failure.
  virtual void fit() = 0;
  virtual Handle(Geom_BSplineSurface) surface() const = 0;
  /// Control points of the result (poles; distinct ones in a periodic direction).
  virtual long coefficients() const = 0;
  /// "nu x nv" of the result.
  virtual std::string shape() const = 0;
  /// Anything the reader of the table needs to know about this run (may be empty).
  virtual std::string notes() const { return {}; }
};

/// sfit::fit_surface (the default method; kAuto: its own choice of rules), bicubic,
/// T = (t, t, t) per axis, `threads` as FitOptions::threads.
std::unique_ptr<Peer> make_sfit(const Rows& rows, double t, bool closed_u, int threads,
                                Parametrization rule = Parametrization::kAuto);

/// OpenCASCADE GeomAPI_PointsToBSplineSurface on the grid (all rows of equal length),
/// DegMin = DegMax = 3, C2, Tol3D = t (a distance at OCCT's own chord-length parameters).
std::unique_ptr<Peer> make_occt_grid(const Rows& rows, double t);

/// OpenCASCADE lofting for ragged rows: GeomAPI_PointsToBSpline per row (degree 3, C2,
/// Tol3D = t/2), then GeomFill_SectionGenerator + GeomFill_AppSurf (degree 3, Tol3d = t/2), the
/// path BRepOffsetAPI_ThruSections takes internally. A closed row is fitted as an open curve
/// through its points with the first point repeated at the end.
std::unique_ptr<Peer> make_occt_loft(const Rows& rows, double t, bool closed_u);

/// SISL s1966 on the grid: tensor-product approximation of order (4, 4) by knot removal from
/// the bilinear interpolant, per-axis tolerance (t, t, t), chord-length parameters.
std::unique_ptr<Peer> make_sisl_grid(const Rows& rows, double t);

/// True if every row has the same number of points.
bool is_grid(const Rows& rows);

}  // namespace sfit::peers
