// Golden bits of fit_surface() on the repository's data: the paper's scheme (method sfit01,
// seam and orient keep, no fold guard) and the default, recorded before the fit driver and the
// registries replaced the two-stage class as the front door, so that any change of a fitted
// surface (counts, control points, parameters, the check) shows here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "sfit/surface_fit.h"
#include "support/test_support.h"

namespace sfit {
namespace {

// FNV-1a over the bits of everything a fit returns that a caller reads.
struct Hash {
  std::uint64_t h = 1469598103934665603ull;
  void bytes(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
  void num(double x) { bytes(&x, sizeof x); }
  void num(long x) { bytes(&x, sizeof x); }
};

std::string digest(const FitResult& r) {
  Hash h;
  h.num(static_cast<long>(r.surface.count_u));
  h.num(static_cast<long>(r.surface.count_v));
  h.num(static_cast<long>(r.surface.degree_u));
  h.num(static_cast<long>(r.surface.degree_v));
  for (const Point& p : r.surface.control)
    for (int a = 0; a < 3; ++a) h.num(p[a]);
  for (double x : r.u) h.num(x);
  for (double x : r.v) h.num(x);
  for (double x : r.v_points) h.num(x);
  for (int a = 0; a < 3; ++a) h.num(r.report.max_deviation[a]);
  h.num(static_cast<long>(r.report.within_tolerance));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h.h));
  return buf;
}

FitOptions paper_scheme(const Rows& rows, double fraction, bool closed_u) {
  FitOptions o;
  o.tolerance = relative_tolerance(rows, fraction);
  o.closed_u = closed_u;
  o.method = FitMethod::kSfit01;
  o.seam = SeamMode::kKeep;
  o.orient = OrientMode::kKeep;
  o.fold_guard = false;
  return o;
}

struct Case {
  const char* file;
  bool closed_u;
  double fraction;
  const char* paper;   // digest of the paper's scheme
  const char* fitted;  // digest of the default (method surface)
};

// Recorded with the code before the fit driver, the same on this machine's g++ 12 -O2 build.
// A digest is of bits: another compiler or flags may round differently and must re-record.
// Re-recorded since: the default on bent_tube when the row rules' normal equations became
// factorised as a band (2026-12-03; the same counts, control points differing at round-off);
// the default on iea3p4mw_blade_ragged9 when closed rows got corner knots (2026-12-03: 36 x 9
// on uniform knots -> 12 x 9 with a crease at the trailing edge; again with the open rows' corner
// changes beside it, docs/method.md 7.13: the same 12 x 9, its bits differing).
const Case kCases[] = {
    {"height_field_small.rows", false, 1e-2, "d75dbc0c85d04540", "fb2efc3cecef9f02"},
    {"bent_tube.rows", true, 1e-3, "6ee0e5cb741de96a", "32d4c5d87fb93467"},
    {"iea3p4mw_blade_ragged9.rows", true, 1e-3, "eccc00c3b622e9f3", "15bc5a849ee626be"},
    {"ship_px121_stations.rows", false, 1e-3, "a4076018fe2182b0", "277c47b8f556177d"},
};

TEST(FitGolden, PaperSchemeIsBitForBitAsRecorded) {
  for (const Case& c : kCases) {
    const Rows rows = test::load_rows(test::example(c.file));
    const FitResult r = fit_surface(rows, paper_scheme(rows, c.fraction, c.closed_u));
    EXPECT_TRUE(r.report.within_tolerance) << c.file;
    EXPECT_EQ(r.report.method, FitMethod::kSfit01) << c.file;
    EXPECT_EQ(digest(r), c.paper) << c.file;
  }
}

TEST(FitGolden, DefaultFitIsBitForBitAsRecorded) {
  for (const Case& c : kCases) {
    const Rows rows = test::load_rows(test::example(c.file));
    FitOptions o;
    o.tolerance = relative_tolerance(rows, c.fraction);
    o.closed_u = c.closed_u;
    const FitResult r = fit_surface(rows, o);
    EXPECT_TRUE(r.report.within_tolerance) << c.file;
    EXPECT_EQ(digest(r), c.fitted) << c.file;
  }
}

}  // namespace
}  // namespace sfit
