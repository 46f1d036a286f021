#include "scattered_lsq.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "banded_cholesky.h"
#include "basis.h"
#include "knots.h"
#include "parallel.h"

namespace sfit::detail {

namespace {

// Points per block of the assembly (fixed, so the sums do not depend on the thread count).
constexpr std::size_t kBlock = 1 << 15;

double domain(int degree, int count, bool closed) {
  return domain_end(degree, count, closed);
}

}  // namespace

ScatteredProblem::ScatteredProblem(const Rows& rows, const ScatteredSpec& spec,
                                   std::vector<double> fu, std::vector<double> fv)
    : rows_(rows), spec_(spec), fu_(std::move(fu)), fv_(std::move(fv)) {}

int ScatteredProblem::min_u() const {
  return spec_.closed_u ? 2 * spec_.degree_u + 1 : spec_.degree_u + 1;
}
int ScatteredProblem::min_v() const {
  return spec_.closed_v ? 2 * spec_.degree_v + 1 : spec_.degree_v + 1;
}

std::vector<double> ScatteredProblem::u_at(int nu) const {
  const double e = domain(spec_.degree_u, nu, spec_.closed_u);
  std::vector<double> u(fu_.size());
  for (std::size_t k = 0; k < u.size(); ++k) u[k] = fu_[k] * e;
  return u;
}
std::vector<double> ScatteredProblem::v_at(int nv) const {
  const double e = domain(spec_.degree_v, nv, spec_.closed_v);
  std::vector<double> v(fv_.size());
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = fv_[k] * e;
  return v;
}

double ScatteredProblem::cost(int nu, int nv) const {
  const int p = spec_.degree_u, q = spec_.degree_v;
  const double band =
      spec_.closed_u ? static_cast<double>(q + 1) * nu
                     : std::min(static_cast<double>(q) * nu + p, static_cast<double>(p) * nv + q);
  return 0.5 * static_cast<double>(nu) * nv * band * band;
}

namespace {

// row[a wv + c] += wx * w[a Q + c] for a <= p, c < Q: runs of Q known at compile time.
template <int Q>
inline void add_runs(double* row, int wv, int p, double wx, const double* w) {
  for (int a = 0; a <= p; ++a, row += wv, w += Q)
    for (int c = 0; c < Q; ++c) row[c] += wx * w[c];
}

// The data term of points whose bases `basis(k, bu, bv)` gives (it fills the p + 1 and q + 1
// values and returns the first control points {f0, f1}), added into `band` and `rhs` (`pts`
// empty: the band only).
template <class Basis>
void add_points(const ScatteredSpec& spec, int nu, int nv, std::size_t count,
                std::span<const Point> pts, std::span<const double> wts, Basis&& basis,
                std::vector<double>& band, std::vector<Point>& rhs) {
  const int p = spec.degree_u, q = spec.degree_v;
  const int wv = 2 * q + 1, W = (2 * p + 1) * wv;
  const int n_local = (p + 1) * (q + 1);
  std::array<double, kMaxDegree + 1> bu, bv;
  std::vector<double> w(n_local);
  std::vector<std::size_t> idx(n_local);
  for (std::size_t k = 0; k < count; ++k) {
    const auto [f0, f1] = basis(k, bu.data(), bv.data());
    const double weight = wts.empty() ? 1.0 : wts[k];
    for (int a = 0; a <= p; ++a)
      for (int c = 0; c <= q; ++c) {
        const int x = a * (q + 1) + c;
        w[x] = bu[a] * bv[c];
        idx[x] = static_cast<std::size_t>(wrap_index(f0 + a, nu)) * nv + wrap_index(f1 + c, nv);
      }
    for (int x = 0; x < n_local; ++x) {
      const double wx = weight * w[x];
      // Product (x, y), y = (a', c'), goes to offset (a' - a + p) wv + (c' - c + q) of x's
      // row: for each a' a run of q + 1 neighbours, added as contiguous runs (the compiler
      // vectorises them; each entry gets the same product as one at a time).
      double* row = band.data() + idx[x] * W + (q - x % (q + 1)) + (p - x / (q + 1)) * wv;
      if (q == 3)
        add_runs<4>(row, wv, p, wx, w.data());
      else
        for (int a2 = 0; a2 <= p; ++a2)
          for (int c2 = 0; c2 <= q; ++c2) row[a2 * wv + c2] += wx * w[a2 * (q + 1) + c2];
      if (!pts.empty()) rhs[idx[x]] += wx * pts[k];
    }
  }
}

}  // namespace

void scattered_add(const ScatteredSpec& spec, int nu, int nv, std::span<const Point> pts,
                   std::span<const double> wts, std::span<const double> fu,
                   std::span<const double> fv, std::vector<double>& band, std::vector<Point>& rhs) {
  const int p = spec.degree_u, q = spec.degree_v;
  const bool cu = spec.closed_u, cv = spec.closed_v;
  const double eu = domain(p, nu, cu), ev = domain(q, nv, cv);
  add_points(
      spec, nu, nv, pts.size(), pts, wts,
      [&](std::size_t k, double* bu, double* bv) {
        return std::pair<int, int>{eval_basis(p, nu, cu, fu[k] * eu, bu),
                                   eval_basis(q, nv, cv, fv[k] * ev, bv)};
      },
      band, rhs);
}

void scattered_add_basis(const ScatteredSpec& spec, int nu, int nv, std::span<const Point> pts,
                         std::span<const int> first_u, std::span<const double> bu,
                         std::span<const int> first_v, std::span<const double> bv,
                         std::vector<double>& band, std::vector<Point>& rhs) {
  const int p = spec.degree_u, q = spec.degree_v;
  add_points(
      spec, nu, nv, first_u.size(), pts, {},
      [&](std::size_t k, double* a, double* b) {
        std::copy_n(&bu[k * (p + 1)], p + 1, a);
        std::copy_n(&bv[k * (q + 1)], q + 1, b);
        return std::pair<int, int>{first_u[k], first_v[k]};
      },
      band, rhs);
}

namespace {

// The stores a search fills pair after pair, kept per thread between solves: a fresh one each
// time cost page faults and the zeroing of new memory (a 5800-unknown pair's factor is 4 MB):
// on the 10^4-point blade at 1e-4 (closed u) 9700 page faults and 616 ms of CPU, 5900 and
// 548 ms kept. The same values are written, so the same bits; a store above kKeptStoreBytes
// (scattered_lsq.h) is given back after its solve.

ScatteredFactor& kept_factor() {
  thread_local ScatteredFactor f;
  return f;
}

std::vector<double>& kept_band() {
  thread_local std::vector<double> band;
  return band;
}

}  // namespace

bool ScatteredProblem::solve(int nu, int nv, double smoothing, Surface& out, double calm,
                             const Point* normal) const {
  if (nu < min_u() || nv < min_v()) return false;
  std::vector<double>& band = kept_band();
  std::vector<Point> rhs;
  assemble(nu, nv, band, rhs);
  const bool ok = scattered_solve(spec_, nu, nv, band, rhs, smoothing, out, calm, normal);
  if (band.capacity() * sizeof(double) > kKeptStoreBytes) band = std::vector<double>();
  return ok;
}

void ScatteredProblem::assemble(int nu, int nv, std::vector<double>& band, std::vector<Point>& rhs,
                                std::span<const double> extra) const {
  const int W = (2 * spec_.degree_u + 1) * (2 * spec_.degree_v + 1);
  const std::size_t N = static_cast<std::size_t>(nu) * nv;
  const std::vector<Point>& pts = rows_.points();
  std::vector<double> combined;
  if (!extra.empty()) {
    const std::vector<double>& own = rows_.weights();
    combined.assign(extra.begin(), extra.end());
    if (!own.empty())
      for (std::size_t k = 0; k < combined.size(); ++k) combined[k] *= own[k];
  }
  const std::vector<double>& wts = extra.empty() ? rows_.weights() : combined;
  const std::size_t n = pts.size(), blocks = (n + kBlock - 1) / kBlock;
  const int threads = std::max(1, std::min<int>(spec_.threads, static_cast<int>(blocks)));
  struct Part {
    std::vector<double> band;
    std::vector<Point> rhs;
  };
  // One store per thread slot; blocks are summed into slot (block % threads) in order, then
  // the slots in order: the same for a given thread count. For any count: per block.
  std::vector<Part> part(blocks);
  auto run_block = [&](std::size_t b) {
    Part& pt = part[b];
    pt.band.assign(N * W, 0.0);
    pt.rhs.assign(N, Point::Zero());
    const std::size_t k0 = b * kBlock, k1 = std::min(n, (b + 1) * kBlock);
    const std::span<const double> wb =
        wts.empty() ? std::span<const double>() : std::span<const double>(wts).subspan(k0, k1 - k0);
    scattered_add(spec_, nu, nv, std::span<const Point>(pts).subspan(k0, k1 - k0), wb,
                  std::span<const double>(fu_).subspan(k0, k1 - k0),
                  std::span<const double>(fv_).subspan(k0, k1 - k0), pt.band, pt.rhs);
  };
  // Memory: a store per block would be blocks x N x W; merge as we go in fixed groups.
  band.assign(N * W, 0.0);
  rhs.assign(N, Point::Zero());
  if (blocks == 1) {
    // One block sums straight into the store: the same bits as 0 + its own store (a sum
    // started at +0 is never -0), without a second zeroed store of N x W per pair.
    scattered_add(spec_, nu, nv, pts, wts, fu_, fv_, band, rhs);
    return;
  }
  for (std::size_t g = 0; g < blocks; g += static_cast<std::size_t>(threads)) {
    const std::size_t m = std::min<std::size_t>(threads, blocks - g);
    parallel_for(m, threads, [&](std::size_t i) { run_block(g + i); });
    for (std::size_t i = 0; i < m; ++i) {
      Part& pt = part[g + i];
      for (std::size_t e = 0; e < band.size(); ++e) band[e] += pt.band[e];
      for (std::size_t e = 0; e < N; ++e) rhs[e] += pt.rhs[e];
      pt = Part{};
    }
  }
}

bool scattered_solve(const ScatteredSpec& spec, int nu, int nv, const std::vector<double>& band,
                     const std::vector<Point>& rhs, double smoothing, Surface& out, double calm,
                     const Point* normal) {
  const std::size_t N = static_cast<std::size_t>(nu) * nv;
  if (rhs.size() != N || spec.closed_v) return false;  // (the rule is open across)
  ScatteredFactor& f = kept_factor();
  struct GiveBack {
    ScatteredFactor& f;
    ~GiveBack() {
      if (f.bytes() > kKeptStoreBytes) f = ScatteredFactor{};
    }
  } give_back{f};
  // The calm term along `normal` only: the other directions from the system without it, both
  // factorised from one assembly.
  const bool along = calm > 0 && normal;
  ScatteredFactor plain;
  if (!f.factor(spec, nu, nv, band, smoothing, calm, along ? &plain : nullptr)) return false;
  std::vector<Point> x = rhs;
  f.solve(x);
  if (along) {
    std::vector<Point> y = rhs;
    plain.solve(y);
    for (std::size_t I = 0; I < N; ++I) x[I] = y[I] + (x[I] - y[I]).dot(*normal) * *normal;
  }
  out.degree_u = spec.degree_u;
  out.degree_v = spec.degree_v;
  out.periodic_u = spec.closed_u;
  out.periodic_v = spec.closed_v;
  out.count_u = nu;
  out.count_v = nv;
  out.control = std::move(x);
  for (const Point& c : out.control)
    if (!c.allFinite()) return false;
  return true;
}

long ScatteredFactor::pos(std::size_t I) const {
  const long i = static_cast<long>(I / nv_), l = static_cast<long>(I % nv_);
  return v_major_ ? l * nu_ + i : i * nv_ + l;
}

bool ScatteredFactor::factor(const ScatteredSpec& spec, int nu, int nv,
                             const std::vector<double>& band, double smoothing, double calm,
                             ScatteredFactor* plain) {
  const int p = spec.degree_u, q = spec.degree_v;
  const bool cu = spec.closed_u, cv = spec.closed_v;
  const int wv = 2 * q + 1, W = (2 * p + 1) * wv;
  const std::size_t N = static_cast<std::size_t>(nu) * nv;
  if (band.size() != N * W || (cu && cv)) return false;
  double trace = 0;
  const int centre = p * wv + q;
  for (std::size_t I = 0; I < N; ++I) trace += band[I * W + centre];
  if (!(trace > 0)) return false;
  const double lambda = smoothing * trace / static_cast<double>(N);
  // The banded system in the ordering of the narrower band (banded_cholesky.h).
  nu_ = nu;
  nv_ = nv;
  const BandOrder order = band_order(p, q, cu, cv, nu, nv);
  v_major_ = order.v_major;
  const long Nb = static_cast<long>(N);
  const long b = order.b, w1 = b + 1;
  b_ = b;
  // A store kept from the last factorisation grows by at least half (a search's pairs grow
  // one after the other: new memory each time cost a page fault per 4 kB on first touch).
  const std::size_t need = static_cast<std::size_t>(Nb * w1);
  if (L_.capacity() < need) {
    L_.clear();  // (nothing to copy)
    L_.reserve(std::max(need, L_.capacity() + L_.capacity() / 2));
  }
  L_.assign(need, 0.0);
  std::vector<double>& L = L_;
  auto at = [&](int i, int l) { return order.at(i, l); };
  // L(r, c) for c <= r at L[r w1 + c - r + b].
  auto add = [&](long r, long c, double x) {
    if (c > r) std::swap(r, c);
    if (r - c > b) return false;
    L[static_cast<std::size_t>(r * w1 + c - r + b)] += x;
    return true;
  };
  for (std::size_t I = 0; I < N; ++I) {
    const int i = static_cast<int>(I / nv), l = static_cast<int>(I % nv);
    const long r = at(i, l);
    for (int da = -p; da <= p; ++da)
      for (int dc = -q; dc <= q; ++dc) {
        const double val = band[I * W + (da + p) * wv + (dc + q)];
        if (val == 0) continue;
        const long c = at((i + da + nu) % nu, (l + dc + nv) % nv);
        if (c > r) continue;  // the upper triangle: its mirror is added from the other side
        if (!add(r, c, val)) return false;
      }
  }
  // Second differences of the net along u (for each l) and along v (for each i).
  auto add_difference = [&](long a0, long a1, long a2) {
    const long ids[3] = {a0, a1, a2};
    const double k[3] = {1, -2, 1};
    for (int x = 0; x < 3; ++x)
      for (int y = 0; y <= x; ++y) {
        // Diagonal once; an off-diagonal pair once (lower triangle), with its own weight.
        if (ids[x] == ids[y] && x != y) {
          add(ids[x], ids[y], 2 * lambda * k[x] * k[y]);
        } else {
          add(ids[x], ids[y], lambda * k[x] * k[y]);
        }
      }
  };
  if (lambda > 0) {
    for (int l = 0; l < nv; ++l)
      for (int i = cu ? 0 : 1; i < (cu ? nu : nu - 1); ++i)
        add_difference(at((i - 1 + nu) % nu, l), at(i, l), at((i + 1) % nu, l));
    for (int i = 0; i < nu; ++i)
      for (int l = cv ? 0 : 1; l < (cv ? nv : nv - 1); ++l)
        add_difference(at(i, (l - 1 + nv) % nv), at(i, l), at(i, (l + 1) % nv));
  }
  if (calm > 0 && plain) {
    // The system without the calm term: this assembly so far.
    plain->nu_ = nu;
    plain->nv_ = nv;
    plain->v_major_ = v_major_;
    plain->b_ = b;
    plain->L_ = L;
  }
  if (calm > 0) {
    // The calm term: first differences where either control point is weakly held.
    const double mu = calm * trace / static_cast<double>(N), weak = kWeaklyHeld * trace / N;
    auto held = [&](int i, int l) {
      return band[(static_cast<std::size_t>(i) * nv + l) * W + centre] >= weak;
    };
    auto add_first = [&](int i0, int l0, int i1, int l1) {
      if (held(i0, l0) && held(i1, l1)) return;
      long r0 = at(i0, l0), r1 = at(i1, l1);
      if (r1 > r0) std::swap(r0, r1);
      if (r0 - r1 > b) return;
      L[static_cast<std::size_t>(r0 * w1 + b)] += mu;
      L[static_cast<std::size_t>(r1 * w1 + b)] += mu;
      L[static_cast<std::size_t>(r0 * w1 + r1 - r0 + b)] -= mu;
    };
    for (int i = 0; i < nu; ++i)
      for (int l = 0; l < nv; ++l) {
        if (cu || i + 1 < nu) add_first(i, l, (i + 1) % nu, l);
        if (cv || l + 1 < nv) add_first(i, l, i, (l + 1) % nv);
      }
  }
  // Banded Cholesky, L L^T, in place (banded_cholesky.h).
  const double floor = 1e-13 * (trace / static_cast<double>(N));
  if (!banded_cholesky(L.data(), Nb, b, floor)) return false;
  return !(calm > 0 && plain) || banded_cholesky(plain->L_.data(), Nb, b, floor);
}

template <class T>
void ScatteredFactor::solve_in_place(std::vector<T>& io) const {
  const std::size_t N = static_cast<std::size_t>(nu_) * nv_;
  std::vector<T> x(N);
  for (std::size_t I = 0; I < N; ++I) x[static_cast<std::size_t>(pos(I))] = io[I];
  banded_substitute(L_.data(), static_cast<long>(N), b_, x.data());
  for (std::size_t I = 0; I < N; ++I) io[I] = x[static_cast<std::size_t>(pos(I))];
}

void ScatteredFactor::solve(std::vector<Point>& x) const {
  solve_in_place(x);
}
void ScatteredFactor::solve(std::vector<double>& x) const {
  solve_in_place(x);
}

}  // namespace sfit::detail
