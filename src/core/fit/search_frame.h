// The surface search's frame for one fit (surface_method.cpp, docs/control-points.md): the
// rows centred on their box, the round-off, and the verdict on a candidate surface. Private.
#pragma once

#include <compare>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include "between_rows.h"
#include "deviation.h"
#include "fit_driver.h"
#include "pair_search.h"
#include "sfit/rows.h"
#include "sfit/surface.h"
#include "sfit/surface_fit.h"
#include "tensor_lsq.h"

namespace sfit::detail {

// Minimax where least squares misses T by at most this factor (FitNorm::kAuto): the minimax
// error at a pair is at least the least-squares one divided by sqrt(points), in practice
// within 10-40 % of it on smooth data (docs/control-points.md measures it).
constexpr double kLinfReach = 1.25;

struct Frame {
 private:
  // The centred rows where the frame made them itself (Frame(rows, o)); from a Centring it
  // refers to the driver's (no copy of the points per fit: 24 MB at 10^6 points).
  std::unique_ptr<const Rows> own_;

 public:
  int threads = 1;
  BoundingBox box, centred_box;
  Point centre = Point::Zero();
  double roundoff = 0;
  const Rows& centred;
  Point tolerance = Point::Zero();
  bool closed_v = false;

  Frame(const Rows& rows, const FitOptions& o);
  /// The same frame from the driver's centring of the rows (fit_driver.h): no second pass,
  /// no copy (the frame refers to `c`'s centred rows: `c` must outlive it).
  Frame(const Centring& c, const FitOptions& o);
  Frame(const Frame&) = delete;
  Frame& operator=(const Frame&) = delete;

 private:
  Frame(const Rows& rows, const FitOptions& o, int threads, const BoundingBox& box);

 public:
  /// Whether a candidate (centred) holds: every point of the rows (or of `sample`, a subset
  /// of them at the same positions) within T per axis and inside the ellipsoid of semi-axes T
  /// around its surface point (the ball of radius T where T is one number), and
  /// every guard (fit_frame.h) passed. The verdict's ratio is the worst |S - D| / T over the
  /// points and axes; without `out` the pass stops once a point misses T by more than
  /// kLinfReach (the ratio is then a value above it: all the search asks), with `out` it is
  /// exact and `out` receives the whole check. `guards` false: the caller runs its own
  /// (Parametrization::kGeometric, whose domain has spans without data: geometric_search.h).
  PairVerdict judge(const Surface& s, std::span<const double> u, std::span<const double> v,
                    DeviationCheck* out = nullptr, const Rows* sample = nullptr,
                    bool guards = true) const;

  /// Neighbouring points of consecutive centred rows (between_rows.h), made at the first call
  /// (safe from any thread).
  const RowPairs& row_pairs() const;

 private:
  mutable std::once_flag pairs_once_;
  mutable RowPairs pairs_;
};

/// The parameter rules the search tries for FitOptions::parametrization (all five for kAuto
/// and kFewest, in the order geometric, uniform, chord, centripetal, paper; then the
/// registered rules that opted in, automatic_rules()). The surface search moves geometric
/// last (surface_method.cpp).
std::vector<Parametrization> rules_of(Parametrization p);
/// The solver's spec for a fit's options at one rule.
TensorSpec spec_of(const FitOptions& o, Parametrization rule, int threads,
                   std::span<const double> seam_offsets);
/// The surface at one pair by one norm (centred), or nullopt where none was made. `ls`: the
/// problem's least-squares surface at that pair where the caller has it (kLinf then refines a
/// copy of it: the same bits as solving it again).
std::optional<Surface> solve_pair(TensorProblem& prob, FitNorm norm, int nu, int nv,
                                  const Point& tolerance, const Surface* ls = nullptr);

/// Surfaces a search keeps so that no pair is solved twice (each is deterministic, so a kept
/// one has the bits a second solve would give): the least-squares surfaces that minimax may
/// refine next (small: minimax_affordable()), and the surfaces that held with the fewest
/// control points so far (ties: all of them), which the result takes instead of remaking.
class KeptSurfaces {
 public:
  struct Key {
    Parametrization rule;
    FitNorm norm;
    int nu, nv;
    auto operator<=>(const Key&) const = default;
  };
  /// A least-squares surface (unraised, as TensorProblem::solve() made it) of the current rule.
  void keep_ls(int nu, int nv, const Surface& s) { ls_[{nu, nv}] = s; }
  const Surface* ls(int nu, int nv) const;
  /// The next rule: its least-squares surfaces are of another problem.
  void next_rule() { ls_.clear(); }
  /// A surface that held: kept where it has no more control points than every one kept.
  void keep_held(const Key& k, const Surface& s);
  const Surface* held(const Key& k) const;

 private:
  std::map<std::pair<int, int>, Surface> ls_;
  std::map<Key, Surface> held_;
  long held_size_ = 0;
};
/// The result of a surface (centred) with its check, in the frame's coordinates and report
/// (frame_result() of fit_frame.h) and the shape measures; method kSurface.
FitResult assemble(const Frame& fr, Surface s, std::vector<double> u, std::vector<double> v,
                   const DeviationCheck& c, const FitOptions& o);

/// FitOptions::counts: the surface at exactly that pair (fixed_counts.cpp).
/// `centring`: the driver's of `rows` where given.
FitResult fit_at_counts(const Rows& rows, const FitOptions& o, double t0,
                        std::span<const double> seam_offsets, const Centring* centring = nullptr);

}  // namespace sfit::detail
