// SISL's grid approximation within a tolerance (s1966). SISL is AGPL: it is linked by this
// optional benchmark only, never by the sfit library.
#include <sisl.h>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>

#include <stdexcept>
#include <vector>

#include "peers.h"

namespace sfit::peers {

namespace {

// A SISL knot vector (n + k values) as OCCT's distinct knots and multiplicities.
void to_occt_knots(const double* t, int n, int k, TColStd_Array1OfReal& knots,
                   TColStd_Array1OfInteger& mults) {
  std::vector<double> v;
  std::vector<int> m;
  for (int i = 0; i < n + k; ++i) {
    if (!v.empty() && t[i] == v.back()) {
      ++m.back();
    } else {
      v.push_back(t[i]);
      m.push_back(1);
    }
  }
  knots.Resize(1, static_cast<int>(v.size()), false);
  mults.Resize(1, static_cast<int>(v.size()), false);
  for (std::size_t i = 0; i < v.size(); ++i) {
    knots(static_cast<int>(i) + 1) = v[i];
    mults(static_cast<int>(i) + 1) = m[i];
  }
}

class SislGrid final : public Peer {
 public:
  SislGrid(const Rows& rows, double t)
      : im1_(static_cast<int>(rows[0].size())), im2_(static_cast<int>(rows.size())), tol_(t) {
    points_.reserve(3 * rows.total_points());
    for (std::size_t j = 0; j < rows.size(); ++j)
      for (const Point& p : rows[j]) points_.insert(points_.end(), {p.x(), p.y(), p.z()});
  }
  ~SislGrid() override {
    if (surface_) freeSurf(surface_);
  }
  void fit() override {
    if (surface_) freeSurf(surface_);
    surface_ = nullptr;
    double eeps[3] = {tol_, tol_, tol_};
    int nend[4] = {0, 0, 0, 0};
    double edgeps[12];
    for (double& e : edgeps) e = tol_;
    double emxerr[3] = {0, 0, 0};
    int stat = 0;
    // ipar 1: mean accumulated chord length; open both ways; afctol 0.5: half of the
    // tolerance for the linear reduction, half for the cubic one; iopt 3: u then v; itmax 5.
    s1966(points_.data(), im1_, im2_, 3, 1, nullptr, nullptr, eeps, nend, 1, 1, edgeps, kAfctol, 3,
          kItmax, 4, 4, &surface_, emxerr, &stat);
    if (stat < 0 || !surface_)
      throw std::runtime_error("s1966 failed, status " + std::to_string(stat));
    for (int k = 0; k < 3; ++k) emxerr_[k] = emxerr[k];
  }
  Handle(Geom_BSplineSurface) surface() const override {
    const SISLSurf* s = surface_;
    TColgp_Array2OfPnt poles(1, s->in1, 1, s->in2);
    for (int j = 0; j < s->in2; ++j)
      for (int i = 0; i < s->in1; ++i) {
        const double* c = s->ecoef + 3 * (static_cast<std::size_t>(j) * s->in1 + i);
        poles(i + 1, j + 1) = gp_Pnt(c[0], c[1], c[2]);
      }
    TColStd_Array1OfReal ku(1, 1), kv(1, 1);
    TColStd_Array1OfInteger mu(1, 1), mv(1, 1);
    to_occt_knots(s->et1, s->in1, s->ik1, ku, mu);
    to_occt_knots(s->et2, s->in2, s->ik2, kv, mv);
    return new Geom_BSplineSurface(poles, ku, kv, mu, mv, s->ik1 - 1, s->ik2 - 1);
  }
  long coefficients() const override { return static_cast<long>(surface_->in1) * surface_->in2; }
  std::string shape() const override {
    return std::to_string(surface_->in1) + "x" + std::to_string(surface_->in2);
  }
  std::string notes() const override {
    return "own bound: " + std::to_string(std::max({emxerr_[0], emxerr_[1], emxerr_[2]}));
  }

  static constexpr double kAfctol = 0.5;
  static constexpr int kItmax = 5;

 private:
  std::vector<double> points_;
  int im1_, im2_;
  double tol_;
  SISLSurf* surface_ = nullptr;
  double emxerr_[3] = {0, 0, 0};
};

}  // namespace

std::unique_ptr<Peer> make_sisl_grid(const Rows& rows, double t) {
  return std::make_unique<SislGrid>(rows, t);
}

}  // namespace sfit::peers
