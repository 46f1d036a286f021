#include "normal_equations.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <algorithm>
#include <array>

#include "banded_cholesky.h"
#include "basis.h"
#include "kron_pcg.h"

namespace sfit::detail {

namespace {
// Below this bound on the factorisation's flops (full_cost()), Eigen's simplicial Cholesky.
constexpr double kSimplicialFlops = 2e8;
// Above this bound, conjugate gradients first (kron_pcg.h; TensorSpec::iterative), where nu
// is at most this share of the shortest row's points: closer to interpolating the rows, the
// rows' Gram matrices differ too much for the Kronecker preconditioner (CG then failed to
// converge in 150 iterations on volcano and the teapot body; 3-25 iterations below it).
constexpr double kIterativeFlops = 1e6;
constexpr double kIterativeShare = 0.75;
// Up to this many flops (N b^2, b the band of the narrower ordering) the system is factorised
// as a band (banded_cholesky.h), before conjugate gradients or a sparse factorisation: no
// triplets, ordering or symbolic analysis (those were a third of the row rules' solves).
constexpr double kBandedFlops = 1e7;

BandOrder spec_order(const TensorSpec& spec, int nu, int nv) {
  return band_order(spec.degree_u, spec.degree_v, spec.closed_u, spec.closed_v, nu, nv);
}

// The system factorised as a band and solved for the three right-hand sides; the same
// matrix as solve()'s sparse one (each stored entry added to its pair).
bool solve_banded(const NormalEquations& ne, Eigen::MatrixX3d& x) {
  const TensorSpec& spec = ne.spec;
  const int nu = ne.nu, nv = ne.nv;
  const int pv = spec.degree_v, wu = spec.degree_u + 1, sv = 2 * pv + 1;
  const BandOrder o = spec_order(spec, nu, nv);
  const long N = static_cast<long>(nu) * nv, b = o.b, w1 = b + 1;
  auto at = [&](int i, int l) { return o.at(i, l); };
  std::vector<double> L(static_cast<std::size_t>(N * w1), 0.0);
  double trace = 0;
  for (int i = 0; i < nu; ++i)
    for (int l = 0; l < nv; ++l) {
      const long r = static_cast<long>(i) * nv + l, R = at(i, l);
      for (int d = 0; d < wu; ++d) {
        if (!spec.closed_u && i + d >= nu) break;
        const int i2 = (i + d) % nu;
        for (int e = 0; e < sv; ++e) {
          const double val = ne.st[(static_cast<std::size_t>(r) * wu + d) * sv + e];
          if (val == 0.0) continue;
          int l2 = l + e - pv;
          if (l2 < 0 || l2 >= nv) {
            if (!spec.closed_v) continue;
            l2 = (l2 + nv) % nv;
          }
          long hi = R, lo = at(i2, l2);
          if (lo > hi) std::swap(lo, hi);
          if (hi - lo > b) return false;  // (cannot happen: the band holds every neighbour)
          L[static_cast<std::size_t>(hi * w1 + lo - hi + b)] += val;
          if (hi == lo) trace += val;
        }
      }
    }
  if (!(trace > 0)) return false;
  if (!banded_cholesky(L.data(), N, b, 1e-13 * (trace / static_cast<double>(N)))) return false;
  std::vector<Point> y(static_cast<std::size_t>(N));
  for (int i = 0; i < nu; ++i)
    for (int l = 0; l < nv; ++l)
      y[at(i, l)] = ne.rhs.row(static_cast<long>(i) * nv + l).transpose();
  banded_substitute(L.data(), N, b, y.data());
  x.resize(N, 3);
  for (int i = 0; i < nu; ++i)
    for (int l = 0; l < nv; ++l) x.row(static_cast<long>(i) * nv + l) = y[at(i, l)].transpose();
  return true;
}
}  // namespace

Eigen::SparseMatrix<double> band_matrix(const double* G, int count, int width, bool periodic) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < count; ++i)
    for (int d = 0; d < width; ++d) {
      if (!periodic && i + d >= count) break;
      const int c = (i + d) % count;
      if (G[i * width + d] == 0.0) continue;
      t.emplace_back(std::min(i, c), std::max(i, c), G[i * width + d]);
    }
  Eigen::SparseMatrix<double> A(count, count);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

void shape(Surface& out, const TensorSpec& spec, int nu, int nv) {
  out.degree_u = spec.degree_u;
  out.degree_v = spec.degree_v;
  out.periodic_u = spec.closed_u;
  out.periodic_v = spec.closed_v;
  out.count_u = nu;
  out.count_v = nv;
  out.control.resize(static_cast<std::size_t>(nu) * nv);
}

double full_cost(const TensorSpec& spec, int nu, int nv) {
  const double n = static_cast<double>(nu) * nv;
  const double band = std::min(static_cast<double>(nu) * spec.degree_v + spec.degree_u,
                               static_cast<double>(nv) * spec.degree_u + spec.degree_v) +
                      1;
  return n * band * band;
}

bool solves_as_band(const TensorSpec& spec, int nu, int nv) {
  if (spec.closed_u && spec.closed_v) return false;
  const double b = static_cast<double>(spec_order(spec, nu, nv).b);
  return static_cast<double>(nu) * nv * b * b <= kBandedFlops;
}

bool tries_cg(const TensorSpec& spec, int nu, int nv, int min_points) {
  return spec.iterative && full_cost(spec, nu, nv) >= kIterativeFlops &&
         nu <= kIterativeShare * min_points;
}

NormalEquations::NormalEquations(const TensorSpec& s, int nu_, int nv_, bool kron_)
    : spec(s), nu(nu_), nv(nv_), kron(kron_) {
  const std::size_t n = static_cast<std::size_t>(nu) * nv;
  const int wu = spec.degree_u + 1, wv = spec.degree_v + 1, sv = 2 * spec.degree_v + 1;
  st.assign(n * wu * sv, 0.0);
  rhs = Eigen::MatrixX3d::Zero(static_cast<Eigen::Index>(n), 3);
  gbar.assign(kron ? static_cast<std::size_t>(nu) * wu : 0, 0.0);
  hs.assign(kron ? static_cast<std::size_t>(nv) * wv : 0, 0.0);
}

void NormalEquations::add_row(const double* G, const Point* R, double v) {
  const int pv = spec.degree_v, wu = spec.degree_u + 1, wv = pv + 1;
  const int sv = 2 * pv + 1;  // l' - l + pv
  std::array<double, kMaxDegree + 1> bv;
  const int fv = eval_basis(pv, nv, spec.closed_v, v, bv.data());
  double s_j = 0;
  if (kron) {
    for (int i = 0; i < nu; ++i) s_j += G[i * wu];
    for (std::size_t k = 0; k < gbar.size(); ++k) gbar[k] += G[k];
    s_sum += s_j;
  }
  for (int a = 0; a < wv; ++a) {
    const int l = wrap_index(fv + a, nv);
    if (kron)
      for (int d = 0; a + d < wv; ++d) hs[l * wv + d] += s_j * bv[a] * bv[a + d];
    for (int i = 0; i < nu; ++i) rhs.row(i * nv + l) += bv[a] * R[i].transpose();
    for (int b = 0; b < wv; ++b) {
      const double wab = bv[a] * bv[b];
      const int dl = b - a + pv;
      for (int i = 0; i < nu; ++i) {
        double* S = &st[((static_cast<std::size_t>(i) * nv + l) * wu) * sv + dl];
        const double* g = &G[i * wu];
        if (b >= a) S[0] += wab * g[0];
        for (int d = 1; d < wu; ++d) S[d * sv] += wab * g[d];
      }
    }
  }
}

bool solve(const NormalEquations& ne, bool try_cg, Surface& out) {
  const TensorSpec& spec = ne.spec;
  const int nu = ne.nu, nv = ne.nv;
  const int pv = spec.degree_v, wu = spec.degree_u + 1, wv = pv + 1, sv = 2 * pv + 1;
  const std::size_t n = static_cast<std::size_t>(nu) * nv;
  Eigen::MatrixX3d x;
  if (solves_as_band(spec, nu, nv)) {
    if (!solve_banded(ne, x) || !x.allFinite()) return false;
    shape(out, spec, nu, nv);
    for (std::size_t k = 0; k < n; ++k) out.control[k] = x.row(static_cast<Eigen::Index>(k));
    return true;
  }
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(n * wu * sv);
  for (int i = 0; i < nu; ++i)
    for (int l = 0; l < nv; ++l) {
      const long r = static_cast<long>(i) * nv + l;
      for (int d = 0; d < wu; ++d) {
        if (!spec.closed_u && i + d >= nu) break;
        const int i2 = (i + d) % nu;
        for (int e = 0; e < sv; ++e) {
          const double x = ne.st[((static_cast<std::size_t>(r)) * wu + d) * sv + e];
          if (x == 0.0) continue;
          int l2 = l + e - pv;
          if (l2 < 0 || l2 >= nv) {
            if (!spec.closed_v) continue;
            l2 = (l2 + nv) % nv;
          }
          const long c = static_cast<long>(i2) * nv + l2;
          trip.emplace_back(std::min(r, c), std::max(r, c), x);
        }
      }
    }
  Eigen::SparseMatrix<double> A(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  A.setFromTriplets(trip.begin(), trip.end());
  bool solved = false;
  if (try_cg && ne.kron && ne.s_sum > 0) {
    std::vector<double> gbar = ne.gbar;
    for (double& g : gbar) g /= ne.s_sum;
    solved = solve_kron_pcg(A, ne.rhs, band_matrix(gbar.data(), nu, wu, spec.closed_u),
                            band_matrix(ne.hs.data(), nv, wv, spec.closed_v), x);
  }
  if (solved) {
    // x is CG's
  } else if (full_cost(spec, nu, nv) < kSimplicialFlops) {
    // Small systems: Eigen's simplicial factorisation. CHOLMOD's supernodal one starts
    // OpenMP threads and BLAS calls whose overhead was a third of a volcano fit at 1e-3.
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Upper> llt(A);
    if (llt.info() != Eigen::Success) return false;
    x = llt.solve(ne.rhs);
    if (llt.info() != Eigen::Success) return false;
  } else {
    Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Upper> llt;
    llt.cholmod().print = 0;  // a singular system is an answer here ("does not hold")
    llt.compute(A);
    if (llt.info() != Eigen::Success) return false;
    x = llt.solve(ne.rhs);
    if (llt.info() != Eigen::Success) return false;
  }
  if (!x.allFinite()) return false;
  shape(out, spec, nu, nv);
  for (std::size_t k = 0; k < n; ++k) out.control[k] = x.row(static_cast<Eigen::Index>(k));
  return true;
}

}  // namespace sfit::detail
