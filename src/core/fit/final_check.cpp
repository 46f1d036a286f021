#include "final_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "deviation.h"
#include "fit_driver.h"
#include "fit_frame.h"
#include "sfit/error.h"
#include "sfit/fit_check.h"

namespace sfit::detail {
namespace {

std::string g(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

// A bound on how far two evaluations of a degree (p, q) B-spline surface with control points
// up to `size` in magnitude may differ: each carries the basis values' relative error (a few
// ulps, Cox-de Boor or de Boor alike) times `size` and the p + q + 2 roundings of its sums;
// twice that covers sfit's evaluator against OpenCASCADE's or a textbook one. 3.6e-3 at 1e12
// for bicubics, 29 ulps there.
double evaluation_roundoff(int p, int q, double size) {
  return (2.0 * (p + q) + 4) * std::numeric_limits<double>::epsilon() * size;
}

}  // namespace

Point roundoff_allowance(const Point& tolerance, double roundoff) {
  Point a;
  for (int k = 0; k < 3; ++k) a[k] = tolerance[k] == 0 ? roundoff : 0.0;
  return a;
}

double double_spacing(double x) {
  x = std::fabs(x);
  return std::nextafter(x, std::numeric_limits<double>::infinity()) - x;
}

void check_offset_digits(const BoundingBox& box, const Point& tolerance, double roundoff) {
  const Point allow = roundoff_allowance(tolerance, roundoff);
  for (int a = 0; a < 3; ++a) {
    const double far = std::max(std::fabs(box.min[a]), std::fabs(box.max[a]));
    const double step = double_spacing(far);
    const double limit = tolerance[a] + allow[a];
    if (step <= limit) continue;
    throw Error(
        ErrorCode::kInputData,
        std::string("the data lie ") + g(far) + " from the origin on " + "xyz"[a] +
            ", where doubles are " + g(step) + " apart: too few digits for the tolerance " +
            (tolerance[a] > 0 ? g(tolerance[a]) : "0 (round-off allowance " + g(allow[a]) + ")") +
            "; move the data nearer the origin or raise the tolerance",
        Place{}, {far, step, tolerance[a]});
  }
}

namespace {

// The check proper of check_as_written() and check_fit_as_written(): sets r's max deviation
// and worst point from r.surface as it stands, returns whether every point holds, and the
// per-axis limit it held them to (T + allowance - the evaluation's round-off).
bool written_check(FitResult& r, const Rows& rows, const Point& tolerance, int threads,
                   Point& limit, Point& size) {
  const Surface& s = r.surface;
  FitReport& rep = r.report;
  const Point allow = roundoff_allowance(tolerance, rep.roundoff);
  size = Point::Zero();
  for (const Point& p : s.control) size = size.cwiseMax(p.cwiseAbs());
  // Held where |S - D| <= T + allowance - the evaluation's round-off, per axis.
  for (int a = 0; a < 3; ++a)
    limit[a] = tolerance[a] + allow[a] - evaluation_roundoff(s.degree_u, s.degree_v, size[a]);
  // Where the evaluation's round-off alone exceeds T (a few ulps of the offset), nothing
  // holds; the check still measures the deviations for the report.
  const bool room = (limit.array() >= 0).all();
  const DeviationCheck c =
      check_deviation(s, rows, r.u, r.v_for_points(), limit.cwiseMax(0.0), 0.0, threads);
  report_deviation(rep, c);
  return c.within && room;
}

}  // namespace

void check_as_written(FitResult& r, const Rows& rows, const FitOptions& o) {
  const Surface& s = r.surface;
  FitReport& rep = r.report;
  const Point allow = roundoff_allowance(o.tolerance, rep.roundoff);
  Point limit, size;
  const bool held_centred = rep.within_tolerance;
  const bool within =
      written_check(r, rows, o.tolerance, threads_for(rows, o.threads), limit, size);
  rep.within_tolerance = held_centred && within;
  if (!held_centred || within) return;
  // The method said it held. Where the surface does not hold in centred coordinates either
  // (surface and data less the box's centre), the method was wrong, not the digits: not within.
  {
    const Centring c = centre_rows(rows, o.threads);  // fit_driver.h: as the fit centred them
    Surface sc = s;
    for (Point& p : sc.control) p -= c.centre;
    if (!check_deviation(sc, c.centred, r.u, r.v_for_points(), o.tolerance, rep.roundoff, c.threads)
             .within) {
      rep.within_tolerance = false;
      return;
    }
  }
  // Held in centred coordinates, not in the data's: the offset took the digits.
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (size[a] > size[axis]) axis = a;
  const Point d = rep.worst_deviation.cwiseAbs();
  int worst = 0;
  for (int a = 1; a < 3; ++a)
    if (d[a] - limit[a] > d[worst] - limit[worst]) worst = a;
  const double slack = evaluation_roundoff(s.degree_u, s.degree_v, size[worst]);
  throw Error(ErrorCode::kInputData,
              std::string("the surface as written, ") + g(size[axis]) + " from the origin on " +
                  "xyz"[axis] + " (doubles " + g(double_spacing(size[axis])) +
                  " apart), cannot be shown to hold the tolerance " +
                  (o.tolerance[worst] > 0 ? g(o.tolerance[worst])
                                          : "0 (round-off allowance " + g(allow[worst]) + ")") +
                  " on " + "xyz"[worst] + ": deviation " + g(d[worst]) + " plus up to " + g(slack) +
                  " of round-off in evaluating it; move the data nearer the origin or raise the "
                  "tolerance",
              Place{.row = rep.worst_row, .point = rep.worst_index},
              {d[worst], o.tolerance[worst]});
}

}  // namespace sfit::detail

namespace sfit {

void check_fit_as_written(FitResult& fit, const Rows& rows, const Point& tolerance, int threads) {
  Point limit, size;
  fit.report.within_tolerance =
      detail::written_check(fit, rows, tolerance, detail::threads_for(rows, threads), limit, size);
}

}  // namespace sfit
