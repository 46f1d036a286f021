// The refit at frozen counts, knots and parameters (sfit/frozen_refit.h) through the public
// headers only (no private include path): unchanged rows give back the fit's own
// least-squares surface; a refit is least squares at the frozen parameters (its normal
// equations' residual, from the public basis, vanishes); its verdict is the public final
// check's; the influence predicts a move exactly (the refit is linear in the data).
#include "sfit/frozen_refit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sfit/error.h"
#include "sfit/fit_check.h"
#include "sfit/surface_eval.h"
#include "sfit/surface_fit.h"

namespace sfit {
namespace {

// Rows over a smooth height field; `ragged`: lengths 31 + (j % 4) * 3 and points crowded
// towards the start (the rows share no u, the general path), else 30 rows of 40 (a grid).
Rows terrain(bool ragged) {
  Rows rows;
  for (int j = 0; j < 30; ++j) {
    const int n = ragged ? 31 + (j % 4) * 3 : 40;
    for (int k = 0; k < n; ++k) {
      const double f = k / (n - 1.0), s = ragged ? f * (0.6 + 0.4 * f) : f, t = j / 29.0;
      rows.push_point(Point(100 * s, 100 * t,
                            10 * std::sin(3 * s) * std::cos(2 * t) + 5 * s * t * t +
                                0.5 * std::sin(17 * s + 11 * t)));
    }
    rows.end_row();
  }
  return rows;
}

// `rows` with point k of row j moved by d.
Rows moved(const Rows& rows, std::size_t j, std::size_t k, const Point& d) {
  Rows out;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t i = 0; i < rows[r].size(); ++i)
      out.push_point(rows[r][i] + (r == j && i == k ? d : Point::Zero()));
    out.end_row();
  }
  return out;
}

FitResult least_squares_fit(const Rows& rows, Parametrization rule) {
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  o.method = FitMethod::kSurface;
  o.parametrization = rule;
  return fit_surface(rows, o);
}

double size_of(const Surface& s) {
  double m = 0;
  for (const Point& c : s.control) m = std::max(m, c.cwiseAbs().maxCoeff());
  return m;
}

// max over control points of |sum_k B_k (D_k - S_k)| / sum_k |B_k| |D_k|: the normal
// equations' residual of `fit` on `rows`, from the public basis of the surface.
double normal_residual(const FitResult& fit, const Rows& rows) {
  const Surface& s = fit.surface;
  std::vector<double> vp;
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (std::size_t k = 0; k < rows[j].size(); ++k) vp.push_back(fit.point_v(j, vp.size()));
  const DirectionBasis bu = direction_basis(s, true, fit.u, 0);
  const DirectionBasis bv = direction_basis(s, false, vp, 0);
  const std::size_t n = s.control.size();
  std::vector<Point> r(n, Point::Zero());
  std::vector<double> scale(n, 0);
  const std::vector<Point>& pts = rows.points();
  for (std::size_t m = 0; m < pts.size(); ++m) {
    const Point e = pts[m] - s.evaluate(fit.u[m], vp[m]);
    for (int x = 0; x <= s.degree_u; ++x)
      for (int y = 0; y <= s.degree_v; ++y) {
        const std::size_t c = static_cast<std::size_t>((bu.first[m] + x) % s.count_u) * s.count_v +
                              (bv.first[m] + y) % s.count_v;
        const double w = bu.d[m * (s.degree_u + 1) + x] * bv.d[m * (s.degree_v + 1) + y];
        r[c] += w * e;
        scale[c] += std::abs(w) * pts[m].norm();
      }
  }
  double worst = 0;
  for (std::size_t c = 0; c < n; ++c)
    if (scale[c] > 0) worst = std::max(worst, r[c].cwiseAbs().maxCoeff() / scale[c]);
  return worst;
}

TEST(FrozenRefit, UnchangedRowsGiveTheFitsOwnLeastSquaresSurface) {
  for (bool ragged : {false, true}) {
    const Rows rows = terrain(ragged);
    const FitResult fit = least_squares_fit(rows, Parametrization::kUniform);
    ASSERT_TRUE(fit.report.within_tolerance);
    ASSERT_EQ(fit.report.norm, FitNorm::kL2);
    std::string why;
    const auto frozen = FrozenRefit::make(rows, fit, why);
    ASSERT_TRUE(frozen) << why;
    const FitResult r = frozen->refit(rows);
    ASSERT_EQ(r.surface.control.size(), fit.surface.control.size());
    double diff = 0;
    for (std::size_t c = 0; c < r.surface.control.size(); ++c)
      diff = std::max(diff, (r.surface.control[c] - fit.surface.control[c]).cwiseAbs().maxCoeff());
    // The fit is least squares to round-off; the refit's smoothing term (relative weight 1e-8,
    // which decides spans without data) is all that separates them: 1.3e-7 of the control
    // points' size on the ragged rows, round-off on the grid.
    EXPECT_LT(normal_residual(fit, rows), 1e-12) << "ragged " << ragged;
    EXPECT_LT(diff, (ragged ? 1e-6 : 1e-9) * size_of(fit.surface)) << "ragged " << ragged;
    EXPECT_TRUE(r.report.within_tolerance);
    EXPECT_EQ(r.u, fit.u);
    EXPECT_NE(r.report.stop_reason.find("quick refit"), std::string::npos);
  }
}

TEST(FrozenRefit, RefitIsLeastSquaresAtTheFrozenParameters) {
  // Every rule the search has, geometric (v per point) included; the fits' own knots.
  for (Parametrization rule :
       {Parametrization::kUniform, Parametrization::kChord, Parametrization::kGeometric}) {
    for (bool ragged : {false, true}) {
      const Rows rows = terrain(ragged);
      const FitResult fit = least_squares_fit(rows, rule);
      std::string why;
      const auto frozen = FrozenRefit::make(rows, fit, why);
      ASSERT_TRUE(frozen) << why;
      const Rows edited = moved(rows, 7, 12, Point(0.3, -0.2, 2.0));
      const FitResult r = frozen->refit(edited);
      EXPECT_LT(normal_residual(r, edited), 1e-6) << to_string(rule) << " ragged " << ragged;
      // Not the fit of other data: the unedited rows' surface is no least squares of these.
      EXPECT_GT(normal_residual(fit, edited), 1e-4) << to_string(rule) << " ragged " << ragged;
    }
  }
}

TEST(FrozenRefit, VerdictIsThePublicFinalChecks) {
  const Rows rows = terrain(true);
  const FitResult fit = least_squares_fit(rows, Parametrization::kChord);
  std::string why;
  const auto frozen = FrozenRefit::make(rows, fit, why);
  ASSERT_TRUE(frozen) << why;
  const Point t = fit.report.tolerance;
  int within = 0, not_within = 0;
  for (double f : {0.0, 0.5, 3.0, 30.0}) {
    const Rows edited = moved(rows, 11, 20, Point(0, 0, f * t.z()));
    const FitResult r = frozen->refit(edited);
    FitResult again = r;
    again.report.within_tolerance = !r.report.within_tolerance;
    check_fit_as_written(again, edited, t);
    EXPECT_EQ(r.report.within_tolerance, again.report.within_tolerance) << f;
    EXPECT_EQ(r.report.max_deviation, again.report.max_deviation) << f;
    // And by the surface's own evaluation, away from the verdict's edge.
    double worst = 0;
    std::size_t m = 0;
    for (std::size_t j = 0; j < edited.size(); ++j)
      for (std::size_t k = 0; k < edited[j].size(); ++k, ++m)
        worst = std::max(
            worst,
            ((edited[j][k] - r.surface.evaluate(r.u[m], r.point_v(j, m))).cwiseAbs().array() /
             t.array())
                .maxCoeff());
    if (worst < 0.99) {
      EXPECT_TRUE(r.report.within_tolerance) << f;
    }
    if (worst > 1.01) {
      EXPECT_FALSE(r.report.within_tolerance) << f;
    }
    (r.report.within_tolerance ? within : not_within)++;
  }
  EXPECT_GT(within, 0);
  EXPECT_GT(not_within, 0);
}

TEST(FrozenRefit, InfluencePredictsAMove) {
  for (bool ragged : {false, true}) {
    const Rows rows = terrain(ragged);
    const FitResult fit = least_squares_fit(rows, Parametrization::kUniform);
    std::string why;
    const auto frozen = FrozenRefit::make(rows, fit, why);
    ASSERT_TRUE(frozen) << why;
    const FitResult base = frozen->refit(rows);
    const Point d(0.4, -0.7, 1.3);
    for (std::size_t j : {0u, 13u, 29u}) {
      const std::size_t k = rows[j].size() / 3;
      const std::vector<double> g = frozen->influence(j, k);
      ASSERT_EQ(g.size(), fit.surface.control.size());
      const FitResult r = frozen->refit(moved(rows, j, k, d));
      double err = 0, moved_by = 0;
      for (std::size_t c = 0; c < g.size(); ++c) {
        const Point delta = r.surface.control[c] - base.surface.control[c];
        err = std::max(err, (delta - g[c] * d).cwiseAbs().maxCoeff());
        moved_by = std::max(moved_by, delta.cwiseAbs().maxCoeff());
      }
      EXPECT_GT(moved_by, 1e-3) << j;
      EXPECT_LT(err, 1e-12 * size_of(base.surface)) << "ragged " << ragged << " row " << j;
    }
  }
}

TEST(FrozenRefit, RefusesWhatItCannotTake) {
  const Rows rows = terrain(false);
  const FitResult fit = least_squares_fit(rows, Parametrization::kUniform);
  std::string why;
  const auto frozen = FrozenRefit::make(rows, fit, why);
  ASSERT_TRUE(frozen) << why;
  // Rows of other sizes, a point outside the rows: usage errors.
  try {
    frozen->refit(terrain(true));
    FAIL() << "rows of other sizes were refitted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kUsage);
  }
  EXPECT_THROW(frozen->influence(30, 0), Error);
  EXPECT_THROW(frozen->influence(0, 40), Error);
  // Weighted rows, and parameters of other rows: not made, and why.
  Rows weighted = rows;
  weighted.set_weights(std::vector<double>(rows.total_points(), 2.0));
  EXPECT_FALSE(FrozenRefit::make(weighted, fit, why));
  EXPECT_NE(why.find("weighted"), std::string::npos) << why;
  EXPECT_FALSE(FrozenRefit::make(moved(rows, 3, 3, Point(0, 0, 50)), fit, why));
  EXPECT_NE(why.find("do not reproduce"), std::string::npos) << why;
}

}  // namespace
}  // namespace sfit
