#include "knots.h"

#include <algorithm>
#include <cmath>

namespace sfit {

std::vector<double> clamped_uniform_knots(int degree, int count) {
  std::vector<double> k(static_cast<std::size_t>(count + degree + 1));
  const int last = count - degree;
  for (int i = 0; i < static_cast<int>(k.size()); ++i)
    k[static_cast<std::size_t>(i)] = std::clamp(i - degree, 0, last);
  return k;
}

std::vector<double> periodic_uniform_knots(int degree, int count) {
  std::vector<double> k(static_cast<std::size_t>(count + 2 * degree + 1));
  for (int i = 0; i < static_cast<int>(k.size()); ++i) k[static_cast<std::size_t>(i)] = i - degree;
  return k;
}

double domain_end(int degree, int count, bool periodic) {
  return periodic ? count : count - degree;
}

namespace {
double wrap(double t, double period) {
  double r = std::fmod(t, period);
  if (r < 0) r += period;
  if (r >= period) r = 0;  // fmod round-off
  return r;
}
}  // namespace

double greville(int degree, int count, bool periodic, int i) {
  if (periodic) return wrap(i - 0.5 * (degree - 1), count);
  if (degree == 0) return i + 0.5;
  // Sum of knots i+1 ... i+degree of the clamped vector, knot m = clamp(m - degree, 0, last).
  const int last = count - degree;
  double s = 0;
  for (int m = i + 1; m <= i + degree; ++m) s += std::clamp(m - degree, 0, last);
  return s / degree;
}

double greville_at(int degree, int count, bool periodic, double x) {
  if (periodic) return wrap(x - 0.5 * (degree - 1), count);
  if (count == 1) return 0.0;
  x = std::clamp(x, 0.0, static_cast<double>(count - 1));
  int m = static_cast<int>(std::floor(x));
  if (m >= count - 1) m = count - 2;
  const double f = x - m;
  const double a = greville(degree, count, false, m);
  const double b = greville(degree, count, false, m + 1);
  return a + f * (b - a);
}

}  // namespace sfit
