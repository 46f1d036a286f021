// libFuzzer target: the whole fit (fit_surface) on small random rows and options.
// Input: 3 option bytes, then .rows text (so the .rows seeds and dictionary apply).
//   byte 0: degree_u = 1 + b % 20; byte 1: degree_v = 1 + b % 20;
//   byte 2: bit 0 closed rows, bit 1 closed row sequence, bit 2 linear count search,
//           bits 3-7 the tolerance: 0 -> T = 0, 1..28 -> 10^(2 - k/3) of the diagonal,
//           29..31 -> per axis (1e-2, 0, 1e-1) of the diagonal rotated by k.
// A fit must either throw Error(kInputData or kToleranceNotMet) with one line, or return a
// finite surface whose report is true: every point evaluated independently lies within the
// tolerance it claims. SFIT_FUZZ_STRICT=1 also makes a fit that misses its tolerance (CLI
// exit 7, thrown or reported) a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "fuzz_common.h"
#include "sfit/io/rows_reader.h"
#include "sfit/surface_fit.h"

namespace {

constexpr std::size_t kMaxPoints = 400;
constexpr std::size_t kMaxRows = 24;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sfit;
  if (size < 3) return 0;
  FitOptions o;
  o.degree_u = 1 + data[0] % 20;
  o.degree_v = 1 + data[1] % 20;
  o.closed_u = data[2] & 1;
  o.closed_v = data[2] & 2;
  o.search = data[2] & 4 ? CountSearch::kLinear : CountSearch::kFast;
  o.threads = 1;
  const int tol = data[2] >> 3;
  Rows rows;
  try {
    rows = io::parse_rows(std::string_view(reinterpret_cast<const char*>(data + 3), size - 3),
                          "fuzz.rows")
               .rows;
  } catch (const Error&) {
    return 0;  // the reader has its own target
  }
  if (rows.total_points() > kMaxPoints || rows.size() > kMaxRows) return 0;
  const double diag = bounding_box(rows).diagonal();
  if (tol == 0) {
    o.tolerance = Point::Zero();
  } else if (tol <= 28) {
    o.tolerance = Point::Constant(std::pow(10.0, 2.0 - tol / 3.0) * diag);
  } else {
    const Point f(1e-2, 0.0, 1e-1);
    for (int a = 0; a < 3; ++a) o.tolerance[a] = f[(a + tol) % 3] * diag;
  }
  if (!o.tolerance.allFinite()) return 0;  // validate() rejects such data before the tolerance

  static const bool strict = std::getenv("SFIT_FUZZ_STRICT") != nullptr;
  FitResult r;
  try {
    r = fit_surface(rows, o);
  } catch (const Error& e) {
    // kToleranceNotMet: the guarantee gave up (CLI exit 7, nothing written); a proper answer.
    fuzz::check_error(e, ErrorCode::kInputData, ErrorCode::kToleranceNotMet);
    if (strict && e.code() == ErrorCode::kToleranceNotMet)
      fuzz::finding("tolerance not met (strict mode)");
    return 0;
  }
  const Surface& s = r.surface;
  if (s.control.size() != static_cast<std::size_t>(s.count_u) * s.count_v)
    fuzz::finding("control array does not match the counts");
  // The fold guard may lower the degree across the rows, down to 1 (docs/seams.md), never
  // along.
  if (s.degree_u != o.degree_u || s.degree_v > o.degree_v || s.degree_v < 1)
    fuzz::finding("a degree other than the one asked for (or a lower one across the rows)");
  if (s.count_u < (o.closed_u ? 1 : s.degree_u + 1) ||
      s.count_v < (o.closed_v ? 1 : s.degree_v + 1))
    fuzz::finding("fewer control points than an order");
  for (const Point& p : s.control)
    if (!p.allFinite()) fuzz::finding("a non-finite control point");
  if (!r.report.max_deviation.allFinite()) fuzz::finding("a non-finite deviation in the report");
  if (r.u.size() != rows.total_points() || r.v.size() != rows.size() ||
      (!r.v_points.empty() && r.v_points.size() != rows.total_points()))
    fuzz::finding("parameters do not match the points");

  // Independent check of the report: evaluate every point, at its own v where the rule gives
  // one per point (geometric parameters: FitResult::v_for_points()).
  // Slack for rounding: the fit runs centred, this evaluation at the data's own offset.
  const BoundingBox box = bounding_box(rows);
  const double offset = box.min.cwiseAbs().cwiseMax(box.max.cwiseAbs()).maxCoeff();
  const double slack = 1e-9 * diag + 1e-13 * offset;
  Point worst = Point::Zero();
  const bool per_point = !r.v_points.empty();
  std::size_t k = 0;
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (const Point& p : rows[j]) {
      const double v = per_point ? r.v_points[k] : r.v[j];
      const Point d = (s.evaluate(r.u[k++], v) - p).cwiseAbs();
      if (!d.allFinite()) fuzz::finding("the surface evaluates to a non-finite point");
      worst = worst.cwiseMax(d);
    }
  for (int a = 0; a < 3; ++a) {
    if (std::abs(worst[a] - r.report.max_deviation[a]) > slack)
      fuzz::finding("report.max_deviation differs from the evaluated deviation");
    if (r.report.within_tolerance && worst[a] > o.tolerance[a] + r.report.roundoff + slack)
      fuzz::finding("report says within tolerance but a point is not");
  }
  if (strict && !r.report.within_tolerance) fuzz::finding("tolerance not met (strict mode)");
  return 0;
}
