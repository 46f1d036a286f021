#include "sfit/surface.h"

#include <array>
#include <string>

#include "basis_knots.h"
#include "knots.h"
#include "sfit/error.h"

namespace sfit {

double Surface::u_end() const {
  return knots_u.uniform() ? domain_end(degree_u, count_u, periodic_u) : knots_u.end();
}
double Surface::v_end() const {
  return knots_v.uniform() ? domain_end(degree_v, count_v, periodic_v) : knots_v.end();
}

namespace {
void check_match(const KnotVector& k, int degree, int count, bool periodic, const char* dir) {
  if (k.uniform()) return;
  if (k.degree() != degree || k.count() != count || k.periodic() != periodic)
    throw Error(ErrorCode::kUsage,
                std::string("knots along ") + dir + " are for degree " +
                    std::to_string(k.degree()) + ", " + std::to_string(k.count()) +
                    " control points" + (k.periodic() ? ", periodic" : ", open") +
                    "; the surface has degree " + std::to_string(degree) + ", " +
                    std::to_string(count) + (periodic ? ", periodic" : ", open"),
                Place{.option = std::string("knots_") + dir},
                {double(k.degree()), double(k.count()), double(degree), double(count)});
}
}  // namespace

void Surface::set_knots_u(KnotVector k) {
  check_match(k, degree_u, count_u, periodic_u, "u");
  knots_u = std::move(k);
}
void Surface::set_knots_v(KnotVector k) {
  check_match(k, degree_v, count_v, periodic_v, "v");
  knots_v = std::move(k);
}

Point Surface::evaluate(double u, double v) const {
  std::array<double, kMaxDegree + 1> bu, bv;
  const int fu = basis_u(*this, u, bu.data());
  const int fv = basis_v(*this, v, bv.data());
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
  const int fu = basis_derivatives_u(*this, u, 2, du.data());
  const int fv = basis_derivatives_v(*this, v, 2, dv.data());
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
  return full_knots(knots_u, degree_u, count_u, periodic_u);
}
std::vector<double> Surface::full_knots_v() const {
  return full_knots(knots_v, degree_v, count_v, periodic_v);
}

}  // namespace sfit
