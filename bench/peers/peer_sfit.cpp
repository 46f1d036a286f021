// sfit itself, through the library call a user makes.
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <algorithm>
#include <optional>
#include <stdexcept>

#include "peers.h"
#include "sfit/surface_fit.h"

namespace sfit::peers {

namespace {

// Knots 0, 1, ..., with multiplicity degree + 1 at the ends of an open direction and 1 in a
// periodic one (then OCCT wraps the `count` distinct poles itself).
void occt_knots(int degree, int count, bool periodic, TColStd_Array1OfReal& k,
                TColStd_Array1OfInteger& m) {
  const int n = periodic ? count + 1 : count - degree + 1;
  k.Resize(1, n, false);
  m.Resize(1, n, false);
  for (int i = 0; i < n; ++i) {
    k(i + 1) = i;
    m(i + 1) = (!periodic && (i == 0 || i == n - 1)) ? degree + 1 : 1;
  }
}

class SfitPeer final : public Peer {
 public:
  SfitPeer(const Rows& rows, double t, bool closed_u, int threads, Parametrization rule)
      : rows_(rows) {
    options_.degree_u = options_.degree_v = 3;
    options_.parametrization = rule;
    options_.tolerance = Point::Constant(t);
    options_.closed_u = closed_u;
    options_.threads = threads;
  }
  void fit() override {
    result_ = fit_surface(rows_, options_);
    if (!result_->report.within_tolerance) throw std::runtime_error("sfit: tolerance not met");
  }
  Handle(Geom_BSplineSurface) surface() const override {
    const Surface& s = result_->surface;
    // The OCCT copy below is on uniform knots (the default's): never check another surface.
    if (s.non_uniform()) throw std::runtime_error("sfit peer: non-uniform knots not exported");
    TColgp_Array2OfPnt poles(1, s.count_u, 1, s.count_v);
    for (int i = 0; i < s.count_u; ++i)
      for (int j = 0; j < s.count_v; ++j) {
        const Point& p = s.at(i, j);
        poles(i + 1, j + 1) = gp_Pnt(p.x(), p.y(), p.z());
      }
    TColStd_Array1OfReal ku(1, 1), kv(1, 1);
    TColStd_Array1OfInteger mu(1, 1), mv(1, 1);
    occt_knots(s.degree_u, s.count_u, s.periodic_u, ku, mu);
    occt_knots(s.degree_v, s.count_v, s.periodic_v, kv, mv);
    return new Geom_BSplineSurface(poles, ku, kv, mu, mv, s.degree_u, s.degree_v, s.periodic_u,
                                   s.periodic_v);
  }
  long coefficients() const override {
    return static_cast<long>(result_->surface.count_u) * result_->surface.count_v;
  }
  std::string shape() const override {
    return std::to_string(result_->surface.count_u) + "x" +
           std::to_string(result_->surface.count_v);
  }
  std::string notes() const override {
    const FitReport& r = result_->report;
    // The two-stage counts are empty where that fit did not run (the surface search on large
    // data: docs/control-points.md).
    auto largest = [](const std::vector<int>& c) {
      return c.empty() ? std::string("-") : std::to_string(*std::max_element(c.begin(), c.end()));
    };
    return "own check: max per-axis deviation " + std::to_string(r.max_deviation.maxCoeff()) +
           (r.within_tolerance ? " <= T" : " > T") + "; method " +
           std::string(to_string(r.method)) + ", " + std::to_string(r.pairs_tried) +
           " pairs tried; max row count " + largest(r.row_counts) + ", max column count " +
           largest(r.column_counts) + ", raised " + std::to_string(r.raised_u) + "/" +
           std::to_string(r.raised_v) + ", tightenings " + std::to_string(r.tightenings) +
           ", solves " + std::to_string(r.solves) + ", " +
           std::string(to_string(r.parametrization)) + " parameters";
  }

 private:
  const Rows& rows_;
  FitOptions options_;
  std::optional<FitResult> result_;
};

}  // namespace

std::unique_ptr<Peer> make_sfit(const Rows& rows, double t, bool closed_u, int threads,
                                Parametrization rule) {
  return std::make_unique<SfitPeer>(rows, t, closed_u, threads, rule);
}

bool is_grid(const Rows& rows) {
  for (std::size_t j = 1; j < rows.size(); ++j)
    if (rows[j].size() != rows[0].size()) return false;
  return rows.size() >= 2 && rows[0].size() >= 2;
}

}  // namespace sfit::peers
