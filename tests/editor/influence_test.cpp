// The drag's linear prediction (src/server/influence.*, include/sfit/frozen_refit.h): the quick
// refit is least squares at the counts, knots and parameters frozen at the drag's start, so S0 + g
// d is the session's own quick refit of the same move (1e-9 of the control points' size), for every
// rule and method; during a drag under way the server says there is none, and why.
#include "influence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "sfit/error.h"
#include "sfit/surface_eval.h"

namespace sfit::server {
namespace {

Rows terrain(int m, int n) {
  Rows rows;
  for (int j = 0; j < m; ++j) {
    for (int k = 0; k < n; ++k) {
      const double s = k / (n - 1.0), t = j / (m - 1.0);
      rows.push_point(Point(100 * s, 100 * t,
                            10 * std::sin(3 * s) * std::cos(2 * t) + 5 * s * t * t +
                                0.5 * std::sin(17 * s + 11 * t)));
    }
    rows.end_row();
  }
  return rows;
}

Session session_at(Parametrization rule) {
  Rows rows = terrain(30, 40);
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  o.parametrization = rule;
  return Session(std::move(rows), o);
}

std::vector<double> doubles(const std::string& b64) {
  static const std::string abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  unsigned v = 0;
  int bits = 0;
  for (char c : b64) {
    if (c == '=') break;
    v = (v << 6) | static_cast<unsigned>(abc.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<unsigned char>((v >> bits) & 255));
    }
  }
  std::vector<double> out(bytes.size() / sizeof(double));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(double));
  return out;
}

// g and S0 of point (row, index) against the session's quick refit of several moves of one
// drag (each 1e-9 of the control points' size); the drag is finished after.
void expect_predicts(Session& s, std::size_t row, std::size_t index) {
  const nlohmann::json j = drag_influence(s, row, index);
  ASSERT_TRUE(j["linear"].get<bool>()) << j.dump();
  EXPECT_EQ(j["version"].get<long>(), s.version());
  const std::vector<double> s0 = doubles(j["surface"]["control_points_f64"]);
  const std::vector<double> g = doubles(j["influence"]);
  ASSERT_EQ(s0.size(), 3 * g.size());
  const Point p0 = s.rows()[row][index];
  EXPECT_EQ(Point(j["point"][0], j["point"][1], j["point"][2]), p0);
  const int nu = s.result().report.count_u, nv = s.result().report.count_v;
  // Several steps of one drag, each compared with the session's quick refit of it.
  for (const Point& d : {Point(0.3, -0.2, 1.5), Point(1, 1, 1), Point(-5, 2, 7), Point(0, 0, 0)}) {
    s.move(row, index, p0 + d, MovePhase::kDrag);
    const FitResult& r = s.shown();
    const Surface& q = r.surface;
    // The counts of the full fit the drag started from, frozen; a least-squares refit,
    // checked at every point and reported as such.
    EXPECT_EQ(q.count_u, nu);
    EXPECT_EQ(q.count_v, nv);
    EXPECT_EQ(r.report.norm, FitNorm::kL2);
    EXPECT_NE(r.report.stop_reason.find("frozen"), std::string::npos) << r.report.stop_reason;
    EXPECT_EQ(r.report.points, s.shown_rows().total_points());
    ASSERT_EQ(static_cast<std::size_t>(q.full_count_u()) * q.full_count_v(), g.size());
    double big = 0, off = 0, moved = 0;
    for (int i = 0, k = 0; i < q.full_count_u(); ++i)
      for (int l = 0; l < q.full_count_v(); ++l, ++k)
        for (int a = 0; a < 3; ++a) {
          big = std::max(big, std::abs(q.full_at(i, l)[a]));
          off = std::max(off, std::abs(s0[3 * k + a] + g[k] * d[a] - q.full_at(i, l)[a]));
          moved = std::max(moved, std::abs(q.full_at(i, l)[a] - s0[3 * k + a]));
        }
    EXPECT_LE(off, 1e-9 * big) << "move " << d.transpose();
    // A real move: the surface follows it (not a comparison of two unmoved surfaces).
    if (d.norm() > 0) {
      EXPECT_GT(moved, 0.01 * d.norm());
    }
    // The report's deviation is the surface's at the frozen parameters.
    Point worst = Point::Zero();
    const Rows& rows = s.shown_rows();
    for (std::size_t jr = 0; jr < rows.size(); ++jr)
      for (std::size_t k = rows.offsets()[jr]; k < rows.offsets()[jr + 1]; ++k)
        worst =
            worst.cwiseMax((q.evaluate(r.u[k], r.point_v(jr, k)) - rows.points()[k]).cwiseAbs());
    EXPECT_LE((worst - r.report.max_deviation).cwiseAbs().maxCoeff(), 1e-9 * big);
    // Least squares: the residual is orthogonal to every control point's basis function
    // (B^T (D - S) = 0, up to the smoothness term of relative weight 1e-8), checked with the
    // public evaluation, independently of the refit's solver.
    {
      const std::size_t n = static_cast<std::size_t>(q.count_u) * q.count_v;
      std::vector<Point> bt(n, Point::Zero());
      std::vector<double> scale(n, 0.0);
      const BoundingBox box = bounding_box(rows);
      const Point centre = 0.5 * (box.min + box.max);
      for (std::size_t jr = 0; jr < rows.size(); ++jr)
        for (std::size_t k = rows.offsets()[jr]; k < rows.offsets()[jr + 1]; ++k) {
          const double u[1] = {r.u[k]}, v[1] = {r.point_v(jr, k)};
          const DirectionBasis bu = direction_basis(q, true, u, 0);
          const DirectionBasis bv = direction_basis(q, false, v, 0);
          const Point res = rows.points()[k] - q.evaluate(u[0], v[0]);
          for (int x = 0; x <= q.degree_u; ++x)
            for (int y = 0; y <= q.degree_v; ++y) {
              const std::size_t c =
                  static_cast<std::size_t>((bu.first[0] + x) % q.count_u) * q.count_v +
                  (bv.first[0] + y) % q.count_v;
              const double w = bu.d[x] * bv.d[y];
              bt[c] += w * res;
              scale[c] += w * (rows.points()[k] - centre).norm();
            }
        }
      double worst_bt = 0, big_scale = 0;
      for (std::size_t c = 0; c < n; ++c) {
        worst_bt = std::max(worst_bt, bt[c].cwiseAbs().maxCoeff());
        big_scale = std::max(big_scale, scale[c]);
      }
      EXPECT_LE(worst_bt, 1e-6 * big_scale) << "B^T (D - S) of the least-squares refit";
    }
    EXPECT_EQ(r.report.within_tolerance,
              (worst.array() <= r.report.tolerance.array() + 1e-9 * big).all());
  }
  double largest = 0;
  for (double x : g) largest = std::max(largest, std::abs(x));
  EXPECT_GT(largest, 0.01);  // the control points near the point follow it
  EXPECT_LT(largest, 10.0);  // near interpolation a control point overshoots its point
  // While the drag is under way, no prediction: the session's rows are the drag's start.
  EXPECT_FALSE(drag_influence(s, row, index)["linear"].get<bool>());
  s.finish_drag();
}

TEST(DragInfluence, PredictsTheQuickRefitOfEveryMove) {
  Session s = session_at(Parametrization::kUniform);
  EXPECT_EQ(s.result().report.method, FitMethod::kSurface);
  expect_predicts(s, 12, 17);
  EXPECT_TRUE(drag_influence(s, 12, 17)["linear"].get<bool>());
}

// Whatever made the full fit, the drag's refit is least squares at its counts, knots and
// parameters frozen: the parameters that move with the points (chord, centripetal,
// geometric) and the two stages' surface are predicted too.
TEST(DragInfluence, PredictsEveryRuleAndMethod) {
  for (Parametrization rule : {Parametrization::kCentripetal, Parametrization::kChord,
                               Parametrization::kGeometric, Parametrization::kPaper}) {
    SCOPED_TRACE(to_string(rule));
    Session s = session_at(rule);
    expect_predicts(s, 3, 4);
  }
  Rows rows = terrain(30, 40);
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  o.method = FitMethod::kSfit01;
  Session s(std::move(rows), o);
  ASSERT_EQ(s.result().report.method, FitMethod::kSfit01);
  SCOPED_TRACE("the two stages");
  expect_predicts(s, 20, 30);
}

// A grid at the paper rule after an edit: the edited row's u is its own, the others share
// theirs (the Kronecker refit with its correction for that row's columns).
TEST(DragInfluence, PredictsAGridWithAnEditedRow) {
  Rows rows = terrain(30, 40);
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  o.parametrization = Parametrization::kPaper;
  o.method = FitMethod::kSfit01;
  Session s(std::move(rows), o);
  const Point p = s.rows()[14][20];
  s.move(14, 20, p + Point(0, 0, 6), MovePhase::kOnce);
  const FitResult& r = s.result();
  ASSERT_NE(r.u[s.rows().offsets()[14] + 5], r.u[s.rows().offsets()[3] + 5]) << "the row's own u";
  expect_predicts(s, 14, 20);
  expect_predicts(s, 3, 7);
}

TEST(DragInfluence, PredictsAdaptiveKnots) {
  Rows rows = terrain(30, 40);
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  o.parametrization = Parametrization::kUniform;
  o.knots = KnotRule::kAdaptive;
  Session s(std::move(rows), o);
  expect_predicts(s, 3, 4);
}

// Closed rows (a periodic direction u): the frozen refit wraps its basis around the seam. With
// the seams kept the fit's parameters are the rows' own, and the drag is predicted.
TEST(DragInfluence, PredictsClosedRows) {
  Rows rows;
  for (int j = 0; j < 12; ++j) {
    for (int k = 0; k < 30; ++k) {
      const double a = 2 * M_PI * k / 30, r = 10 + 0.5 * std::sin(3 * a + 0.4 * j);
      rows.push_point(Point(r * std::cos(a), r * std::sin(a), 2.0 * j + 0.1 * std::cos(a)));
    }
    rows.end_row();
  }
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  o.closed_u = true;
  o.seam = SeamMode::kKeep;
  o.orient = OrientMode::kKeep;
  Session s(std::move(rows), o);
  ASSERT_TRUE(s.result().surface.periodic_u);
  expect_predicts(s, 5, 0);  // the seam's own point
  expect_predicts(s, 7, 29);
}

// Where the frozen refit cannot be made the server says why (and the drag refits as before).
TEST(DragInfluence, NoneForWeightedRows) {
  Rows rows = terrain(30, 40);
  rows.set_weights(std::vector<double>(rows.total_points(), 2.0));
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  Session s(std::move(rows), o);
  const nlohmann::json j = drag_influence(s, 3, 4);
  EXPECT_FALSE(j["linear"].get<bool>());
  EXPECT_EQ(j["why"].get<std::string>(), "weighted rows") << j.dump();
  EXPECT_FALSE(j.contains("influence"));
}

// A frozen drag step to a coordinate that is not a number is refused as fit_surface() refuses
// it, and the drag's state stays where it was.
TEST(DragInfluence, AFrozenDragStepRefusesANonFiniteCoordinate) {
  Session s = session_at(Parametrization::kUniform);
  const Point p = s.rows()[4][5];
  s.move(4, 5, p + Point(0, 0, 1), MovePhase::kDrag);
  const long v = s.version();
  try {
    s.move(4, 5, Point(p.x(), std::nan(""), p.z()), MovePhase::kDrag);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputData);
  }
  EXPECT_EQ(s.version(), v);
  EXPECT_EQ(s.shown_rows()[4][5], p + Point(0, 0, 1));
  EXPECT_TRUE(s.shown().surface.control[0].allFinite());
  s.finish_drag();
}

TEST(DragInfluence, ANonexistentPointIsAUsageError) {
  Session s = session_at(Parametrization::kUniform);
  try {
    drag_influence(s, 30, 0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kUsage);
  }
  EXPECT_THROW(drag_influence(s, 0, 40), Error);
}

}  // namespace
}  // namespace sfit::server
