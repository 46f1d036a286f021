#include "sfit/surface.h"

#include <array>

#include "basis.h"
#include "knots.h"

namespace sfit {

double Surface::u_end() const {
  return domain_end(degree_u, count_u, periodic_u);
}
double Surface::v_end() const {
  return domain_end(degree_v, count_v, periodic_v);
}

Point Surface::evaluate(double u, double v) const {
  std::array<double, kMaxDegree + 1> bu, bv;
  const int fu = eval_basis(degree_u, count_u, periodic_u, u, bu.data());
  const int fv = eval_basis(degree_v, count_v, periodic_v, v, bv.data());
  Point s = Point::Zero();
  for (int a = 0; a <= degree_u; ++a) {
    Point row = Point::Zero();
    const int i = wrap_index(fu + a, count_u);
    for (int b = 0; b <= degree_v; ++b) row += bv[b] * at(i, wrap_index(fv + b, count_v));
    s += bu[a] * row;
  }
  return s;
}

void Surface::derivatives(double u, double v, Point out[6]) const {
  constexpr int M = kMaxDegree + 1;
  std::array<double, 3 * M> du, dv;
  const int pu = degree_u, pv = degree_v;
  const int fu = eval_basis_derivatives(pu, count_u, periodic_u, u, 2, du.data());
  const int fv = eval_basis_derivatives(pv, count_v, periodic_v, v, 2, dv.data());
  for (int k = 0; k < 6; ++k) out[k] = Point::Zero();
  for (int a = 0; a <= pu; ++a) {
    const int i = wrap_index(fu + a, count_u);
    Point c0 = Point::Zero(), c1 = Point::Zero(), c2 = Point::Zero();
    for (int b = 0; b <= pv; ++b) {
      const Point& P = at(i, wrap_index(fv + b, count_v));
      c0 += dv[b] * P;
      c1 += dv[(pv + 1) + b] * P;
      c2 += dv[2 * (pv + 1) + b] * P;
    }
    const double n0 = du[a], n1 = du[(pu + 1) + a], n2 = du[2 * (pu + 1) + a];
    out[0] += n0 * c0;
    out[1] += n1 * c0;
    out[2] += n0 * c1;
    out[3] += n2 * c0;
    out[4] += n1 * c1;
    out[5] += n0 * c2;
  }
}

std::vector<double> Surface::full_knots_u() const {
  return periodic_u ? periodic_uniform_knots(degree_u, count_u)
                    : clamped_uniform_knots(degree_u, count_u);
}
std::vector<double> Surface::full_knots_v() const {
  return periodic_v ? periodic_uniform_knots(degree_v, count_v)
                    : clamped_uniform_knots(degree_v, count_v);
}

}  // namespace sfit
