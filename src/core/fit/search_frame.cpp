#include "search_frame.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "basis_knots.h"
#include "fit_frame.h"
#include "fit_registry.h"
#include "minimax.h"
#include "parallel.h"
#include "sfit/fold_check.h"

namespace sfit::detail {

namespace {

struct PointsVerdict {
  bool within = true;  // every point within T per axis (+ round-off where T = 0)
  bool near = true;    // every point inside the ellipsoid of semi-axes T (+ round-off where 0)
  double ratio = 0;    // the worst |S - D|_a / T_a (a lower bound where the pass stopped)
};

// One pass over the points, by iso-curves as check_deviation() (deviation.h): the per-axis
// check, the distance check and the worst ratio together, stopping once the ratio passes
// `stop_ratio`. The distance check: the per-axis one allows up to sqrt(3) T; the closest-point
// checker of the peer benchmark (docs/bench_peers.md) counts a point whose distance to the
// surface exceeds T, so the search asks this too (the closest distance is at most this one).
// Per axis: sum_a (d_a / T_a)^2 <= 1, the ball of radius T where T is the same on every axis,
// and never tighter on one axis than its own T (min T there held z to 0.001 under
// T = (0.001, 0.001, 0.5), leaving the search nothing below interpolation).
// Fixed blocks of rows, merged in order: the same verdict for any thread count (a stopped
// pass's ratio only says that it passed `stop_ratio`).
PointsVerdict check_points(const Surface& s, const Rows& rows, std::span<const double> u,
                           std::span<const double> v, const Point& tol, double roundoff,
                           double stop_ratio, int threads) {
  Point semi;  // T, plus the round-off allowance only on an axis where T = 0
  for (int a = 0; a < 3; ++a) semi[a] = tol[a] + (tol[a] == 0 ? roundoff : 0.0);
  const Point inverse = semi.array().inverse().matrix();
  const std::size_t M = rows.size(), per = 16, n_blocks = (M + per - 1) / per;
  std::vector<PointsVerdict> part(n_blocks);
  std::atomic<bool> stop{false};
  parallel_for(n_blocks, threads, [&](std::size_t b) {
    std::array<double, kMaxDegree + 1> bu, bv;
    std::vector<Point> iso(static_cast<std::size_t>(s.count_u));
    PointsVerdict& out = part[b];
    const bool per_point = v.size() != M;  // FitResult::v_points
    RowBasis row_basis(s);  // kept across rows with the same u, as check_deviation() does
    for (std::size_t j = b * per; j < std::min(M, (b + 1) * per) && !stop.load(); ++j) {
      const int fv = per_point ? 0 : basis_v(s, v[j], bv.data());
      for (int i = 0; i < s.count_u && !per_point; ++i) {
        Point q = Point::Zero();
        for (int c = 0; c <= s.degree_v; ++c) q += bv[c] * s.at(i, wrap_index(fv + c, s.count_v));
        iso[i] = q;
      }
      const auto row = rows[j];
      const std::span<const double> uj = u.subspan(rows.offsets()[j], row.size());
      if (!per_point) row_basis.of(uj);
      for (std::size_t k = 0; k < row.size(); ++k) {
        Point p = Point::Zero();
        if (per_point) {
          const int fu = basis_u(s, uj[k], bu.data());
          p = point_at(s, bu.data(), fu, v[rows.offsets()[j] + k]);
        } else {
          const double* bk = row_basis.values(k);
          const int fu = row_basis.first(k);
          for (int a = 0; a <= s.degree_u; ++a) p += bk[a] * iso[wrap_index(fu + a, s.count_u)];
        }
        const Point d = p - row[k];
        const Point ad = d.cwiseAbs();
        if (!ad.allFinite()) {
          out = {false, false, std::numeric_limits<double>::infinity()};
          stop.store(true);
          return;
        }
        for (int a = 0; a < 3; ++a) {
          if (ad[a] > tol[a] + (tol[a] == 0 ? roundoff : 0.0)) out.within = false;
          out.ratio = std::max(
              out.ratio, tol[a] > 0 ? ad[a] / tol[a] : (ad[a] > roundoff ? ad[a] / roundoff : 0));
        }
        if (!(d.cwiseProduct(inverse).squaredNorm() <= 1)) out.near = false;
      }
      if (!out.within && out.ratio > stop_ratio) {
        stop.store(true);
        return;
      }
    }
  });
  PointsVerdict all;
  for (const PointsVerdict& p : part) {
    all.within = all.within && p.within;
    all.near = all.near && p.near;
    all.ratio = std::max(all.ratio, p.ratio);
  }
  return all;
}

}  // namespace

namespace {
// The rows less the centre of their box (the frame's own copy).
std::unique_ptr<const Rows> centred_copy(const Rows& rows, int threads, const Point& centre) {
  auto out = std::make_unique<Rows>(rows);
  parallel_for(rows.size(), threads, [&](std::size_t j) {
    for (Point& p : out->mutable_row(j)) p -= centre;
  });
  return out;
}
int frame_threads(const Rows& rows, const FitOptions& o) {
  return threads_for(rows, o.threads);
}
Point box_centre(const BoundingBox& b) {
  return 0.5 * (b.min + b.max);
}
}  // namespace

Frame::Frame(const Rows& rows, const FitOptions& o)
    : Frame(rows, o, frame_threads(rows, o), box_of(rows, frame_threads(rows, o))) {}

Frame::Frame(const Rows& rows, const FitOptions& o, int t, const BoundingBox& b)
    : own_(centred_copy(rows, t, box_centre(b))),
      threads(t),
      box(b),
      centred_box{b.min - box_centre(b), b.max - box_centre(b)},
      centre(box_centre(b)),
      roundoff(kRoundoffRelative * b.diagonal()),
      centred(*own_),
      tolerance(o.tolerance),
      closed_v(o.closed_v) {}

Frame::Frame(const Centring& c, const FitOptions& o)
    : threads(c.threads),
      box(c.box),
      centred_box{c.box.min - c.centre, c.box.max - c.centre},
      centre(c.centre),
      roundoff(c.roundoff),
      centred(c.centred),
      tolerance(o.tolerance),
      closed_v(o.closed_v) {}

const RowPairs& Frame::row_pairs() const {
  std::call_once(pairs_once_, [this] { pairs_ = detail::row_pairs(centred, closed_v); });
  return pairs_;
}

PairVerdict Frame::judge(const Surface& s, std::span<const double> u, std::span<const double> v,
                         DeviationCheck* out, const Rows* sample, bool guards) const {
  const Rows& r = sample ? *sample : centred;
  const PointsVerdict p =
      check_points(s, r, u, v, tolerance, roundoff,
                   out ? std::numeric_limits<double>::infinity() : kLinfReach, threads);
  if (out) *out = check_deviation(s, r, u, v, tolerance, roundoff, threads);
  return {p.within && p.near && (!guards || !failed_guard(s, centred_box)), p.ratio};
}

std::vector<Parametrization> rules_of(Parametrization p) {
  if (p != Parametrization::kAuto && p != Parametrization::kFewest) return {p};
  std::vector<Parametrization> out = {Parametrization::kGeometric, Parametrization::kUniform,
                                      Parametrization::kChord, Parametrization::kCentripetal,
                                      Parametrization::kPaper};
  // Registered rules that opted in (sfit/fit_registry.h, RuleUse::kAlsoAuto), after the
  // built-ins: a tie keeps the built-in.
  for (Parametrization r : automatic_rules()) out.push_back(r);
  return out;
}

TensorSpec spec_of(const FitOptions& o, Parametrization rule, int threads,
                   std::span<const double> seam_offsets) {
  return TensorSpec{o.degree_u,
                    o.degree_v,
                    o.closed_u,
                    o.closed_v,
                    rule,
                    threads,
                    std::vector<double>(seam_offsets.begin(), seam_offsets.end())};
}

// The surface at one pair by one norm (centred), or nullopt where none was made.
std::optional<Surface> solve_pair(TensorProblem& prob, FitNorm norm, int nu, int nv,
                                  const Point& tolerance, const Surface* ls) {
  Surface s;
  if (ls) {
    s = *ls;
  } else if (!prob.solve(nu, nv, s)) {
    return std::nullopt;
  }
  if (norm == FitNorm::kLinf) {
    if (!minimax_refine(prob.rows(), prob.u_at(nu), prob.v_at(nv), tolerance, s))
      return std::nullopt;
  }
  return s;
}

const Surface* KeptSurfaces::ls(int nu, int nv) const {
  auto it = ls_.find({nu, nv});
  return it == ls_.end() ? nullptr : &it->second;
}

void KeptSurfaces::keep_held(const Key& k, const Surface& s) {
  const long size = static_cast<long>(k.nu) * k.nv;
  if (!held_.empty() && size > held_size_) return;
  if (held_.empty() || size < held_size_) held_.clear();
  held_size_ = size;
  held_[k] = s;
}

const Surface* KeptSurfaces::held(const Key& k) const {
  auto it = held_.find(k);
  return it == held_.end() ? nullptr : &it->second;
}

FitResult assemble(const Frame& fr, Surface s, std::vector<double> u, std::vector<double> v,
                   const DeviationCheck& c, const FitOptions& o) {
  // Shape measures (fold_check.h, docs/seams.md) on the centred surface and rows.
  const ShapeMeasures m = measure_shape(s, fr.centred, u, v, fr.centred_box, o.closed_u);
  FitResult out = frame_result(std::move(s), std::move(u), std::move(v), FitReport{}, c, m,
                               fr.centred, fr.centre, fr.roundoff, o);
  out.report.method = FitMethod::kSurface;
  return out;
}

}  // namespace sfit::detail
