// The drag's linear prediction (src/server/influence.*): where the quick refit is linear in
// the moved point, S0 + g d is the session's own quick refit of the same move (1e-9 of the
// control points' size); where it is not (parameters that move with the point, a drag under
// way), the server says so and why.
#include "influence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "sfit/error.h"

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

TEST(DragInfluence, PredictsTheQuickRefitOfEveryMove) {
  Session s = session_at(Parametrization::kUniform);
  const std::size_t row = 12, index = 17;
  const nlohmann::json j = drag_influence(s, row, index);
  ASSERT_TRUE(j["linear"].get<bool>()) << j.dump();
  EXPECT_EQ(j["version"].get<long>(), s.version());
  const std::vector<double> s0 = doubles(j["surface"]["control_points_f64"]);
  const std::vector<double> g = doubles(j["influence"]);
  ASSERT_EQ(s0.size(), 3 * g.size());
  const Point p0 = s.rows()[row][index];
  EXPECT_EQ(Point(j["point"][0], j["point"][1], j["point"][2]), p0);
  // Several steps of one drag, each compared with the session's quick refit of it.
  for (const Point& d : {Point(0.3, -0.2, 1.5), Point(1, 1, 1), Point(-5, 2, 7), Point(0, 0, 0)}) {
    s.move(row, index, p0 + d, MovePhase::kDrag);
    const Surface& q = s.shown().surface;
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
  }
  double largest = 0;
  for (double x : g) largest = std::max(largest, std::abs(x));
  EXPECT_GT(largest, 0.01);  // the control points near the point follow it
  EXPECT_LT(largest, 1.0);
  // While the drag is under way, no prediction: the session's rows are the drag's start.
  EXPECT_FALSE(drag_influence(s, row, index)["linear"].get<bool>());
  s.finish_drag();
  EXPECT_TRUE(drag_influence(s, row, index)["linear"].get<bool>());
}

TEST(DragInfluence, NoneWhereTheParametersMoveWithThePoint) {
  for (Parametrization rule : {Parametrization::kCentripetal, Parametrization::kChord}) {
    Session s = session_at(rule);
    const nlohmann::json j = drag_influence(s, 3, 4);
    EXPECT_FALSE(j["linear"].get<bool>());
    EXPECT_NE(j["why"].get<std::string>().find("move with the point"), std::string::npos)
        << j.dump();
    EXPECT_FALSE(j.contains("influence"));
  }
}

TEST(DragInfluence, NoneWithAdaptiveKnots) {
  Rows rows = terrain(30, 40);
  FitOptions o;
  o.tolerance = relative_tolerance(rows, 1e-3);
  o.parametrization = Parametrization::kUniform;
  o.knots = KnotRule::kAdaptive;
  Session s(std::move(rows), o);
  const nlohmann::json j = drag_influence(s, 3, 4);
  EXPECT_FALSE(j["linear"].get<bool>());
  EXPECT_NE(j["why"].get<std::string>().find("adaptive knots"), std::string::npos) << j.dump();
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
