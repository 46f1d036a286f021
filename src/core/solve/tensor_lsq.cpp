#include "tensor_lsq.h"

#include <Eigen/Sparse>
#include <algorithm>
#include <array>
#include <cmath>

#include "aligned_fit.h"
#include "basis.h"
#include "fit_frame.h"
#include "normal_equations.h"
#include "parallel.h"
#include "parameters.h"

namespace sfit::detail {

namespace {
// Moments kept per problem (one entry per nu): a bisection over nu for one nv and the next
// nv's bisection revisit the same few nu.
constexpr std::size_t kMomentBytes = std::size_t{256} << 20;
// Row j resampled at fraction s of its positions f (ascending; closed rows wrap to point 0).
Point resample(std::span<const Point> row, std::span<const double> f, double s, bool closed) {
  const std::size_t n = row.size();
  if (n == 1) return row[0];
  const std::size_t k =
      static_cast<std::size_t>(std::upper_bound(f.begin(), f.end(), s) - f.begin());
  if (k == 0) return row[0];
  const double f0 = f[k - 1];
  const double f1 = k < n ? f[k] : (closed ? 1.0 : f[n - 1]);
  const Point& p0 = row[k - 1];
  const Point& p1 = k < n ? row[k] : (closed ? row[0] : row[n - 1]);
  const double w = f1 > f0 ? (s - f0) / (f1 - f0) : 0.0;
  return p0 + std::clamp(w, 0.0, 1.0) * (p1 - p0);
}
// Whether every row has the same points' positions (so the same u at any nu, and one Gram
// matrix: the separable solve), e.g. a grid evenly spaced along its rows at any rule.
bool same_positions(const Rows& rows, const std::vector<double>& positions) {
  const std::size_t n = rows[0].size();
  if (positions.size() != rows.total_points()) return false;
  for (std::size_t j = 1; j < rows.size(); ++j)
    if (rows[j].size() != n || !std::equal(positions.begin(), positions.begin() + n,
                                           positions.begin() + rows.offsets()[j]))
      return false;
  return true;
}
}  // namespace

std::vector<double> positions_across(const Rows& rows, const std::vector<double>& positions_u,
                                     Parametrization rule, bool closed_u, bool closed_v) {
  const std::size_t M = rows.size();
  std::vector<Point> column(M);
  if (rule == Parametrization::kUniform || rule == Parametrization::kPaper)
    return normalized_positions(column, Parametrization::kUniform, closed_v);
  std::size_t lo = rows[0].size(), hi = lo;
  for (std::size_t j = 0; j < M; ++j) {
    lo = std::min(lo, rows[j].size());
    hi = std::max(hi, rows[j].size());
  }
  const bool grid = lo == hi;
  const std::size_t K = grid ? lo : std::clamp<std::size_t>(lo, 2, 64);
  std::vector<double> sum(M, 0.0);
  std::size_t used = 0;
  for (std::size_t k = 0; k < K; ++k) {
    const double s = closed_u ? static_cast<double>(k) / K : static_cast<double>(k) / (K - 1);
    for (std::size_t j = 0; j < M; ++j) {
      const auto row = rows[j];
      column[j] = grid ? row[k]
                       : resample(row,
                                  std::span<const double>(positions_u.data() + rows.offsets()[j],
                                                          row.size()),
                                  s, closed_u);
    }
    bool coincide = true;
    for (const Point& p : column) coincide = coincide && p == column[0];
    if (coincide) continue;
    const auto f = normalized_positions(column, rule, closed_v);
    for (std::size_t j = 0; j < M; ++j) sum[j] += f[j];
    ++used;
  }
  if (used == 0) return normalized_positions(column, Parametrization::kUniform, closed_v);
  for (double& f : sum) f /= static_cast<double>(used);
  if (!closed_v) sum.back() = 1.0;
  sum.front() = 0.0;
  return sum;
}

struct TensorProblem::Moments {
  int nu = 0;
  std::vector<double> u;     // per point
  std::vector<double> gram;  // per row (one when shared): nu x (degree_u + 1), G(i, i + d)
  std::vector<Point> rhs;    // per row: nu, B^T D
  std::size_t bytes() const {
    return sizeof(double) * (u.size() + gram.size()) + sizeof(Point) * rhs.size();
  }
};

TensorProblem::TensorProblem(const Rows& rows, const TensorSpec& spec) : rows_(rows), spec_(spec) {
  const std::size_t M = rows.size();
  std::size_t lo = rows[0].size(), hi = lo;
  for (std::size_t j = 0; j < M; ++j) {
    lo = std::min(lo, rows[j].size());
    hi = std::max(hi, rows[j].size());
  }
  max_u_ = std::max<int>(min_u(), static_cast<int>(hi));
  max_v_ = std::max<int>(min_v(), static_cast<int>(M));
  min_points_ = static_cast<int>(lo);
  const bool shifted = !spec.seam_offsets.empty() && spec.rule != Parametrization::kPaper;
  shared_u_ = lo == hi && !shifted &&
              (spec.rule == Parametrization::kPaper || spec.rule == Parametrization::kUniform);
  if (spec.rule != Parametrization::kPaper) {
    positions_u_.resize(rows.total_points());
    parallel_for(M, spec.threads, [&](std::size_t j) {
      auto f = normalized_positions(rows[j], spec.rule, spec.closed_u);
      if (shifted) shift_positions(f, spec.seam_offsets[j]);
      std::copy(f.begin(), f.end(), positions_u_.begin() + rows.offsets()[j]);
    });
    positions_v_ = positions_across(rows, positions_u_, spec.rule, spec.closed_u, spec.closed_v);
    shared_u_ = shared_u_ || same_positions(rows, positions_u_);
  }
  shared_u_ = shared_u_ && !weights_matter(rows);  // one Gram matrix needs the same weights
}

TensorProblem::TensorProblem(const Rows& rows, const TensorSpec& spec,
                             std::vector<double> positions_u, std::vector<double> positions_v)
    : rows_(rows), spec_(spec) {
  std::size_t hi = 0, lo = rows[0].size();
  for (std::size_t j = 0; j < rows.size(); ++j) {
    hi = std::max(hi, rows[j].size());
    lo = std::min(lo, rows[j].size());
  }
  min_points_ = static_cast<int>(lo);
  max_u_ = std::max<int>(min_u(), static_cast<int>(hi));
  max_v_ = std::max<int>(min_v(), static_cast<int>(rows.size()));
  positions_u_ = std::move(positions_u);
  shared_u_ = same_positions(rows, positions_u_) && !weights_matter(rows);
  positions_v_ = std::move(positions_v);
}

Rows subsample(const Rows& rows, std::size_t step, const std::vector<double>& positions,
               std::vector<double>& sub_positions) {
  Rows out;
  sub_positions.clear();
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const auto row = rows[j];
    const auto weights = rows.row_weights(j);
    for (std::size_t k = 0; k < row.size(); ++k)
      if (k % step == 0 || k + 1 == row.size()) {
        out.push_point(row[k]);
        if (!weights.empty()) out.push_weight(weights[k]);
        if (!positions.empty()) sub_positions.push_back(positions[rows.offsets()[j] + k]);
      }
    out.end_row();
  }
  return out;
}

TensorProblem::~TensorProblem() = default;

std::vector<double> TensorProblem::v_at(int nv) const {
  const int M = static_cast<int>(rows_.size());
  if (spec_.rule == Parametrization::kPaper)
    return paper_parameters(spec_.degree_v, nv, spec_.closed_v, M);
  return scaled_parameters(spec_.degree_v, nv, spec_.closed_v, positions_v_);
}

const std::vector<double>& TensorProblem::u_at(int nu) {
  return moments(nu).u;
}

const TensorProblem::Moments& TensorProblem::moments(int nu) {
  auto it = cache_.find(nu);
  if (it != cache_.end()) return *it->second;
  auto m = std::make_unique<Moments>();
  m->nu = nu;
  const int p = spec_.degree_u, w = p + 1;
  const std::size_t M = rows_.size();
  const auto& off = rows_.offsets();
  m->u.resize(rows_.total_points());
  const std::size_t n_gram = shared_u_ ? 1 : M;
  m->gram.assign(n_gram * nu * w, 0.0);
  m->rhs.assign(M * nu, Point::Zero());
  auto params = [&](std::size_t j) {
    const int n = static_cast<int>(rows_[j].size());
    return spec_.rule == Parametrization::kPaper
               ? paper_parameters(p, nu, spec_.closed_u, n)
               : scaled_parameters(p, nu, spec_.closed_u,
                                   std::span<const double>(positions_u_.data() + off[j], n));
  };
  // Rows that share their u (no weights) share every point's basis: evaluated once, not per
  // row (the same values, so the same bits; a grid's pass is then its B^T D alone).
  std::vector<double> shared_t, shared_basis;
  std::vector<int> shared_first;
  if (shared_u_) {
    shared_t = params(0);
    shared_first.resize(shared_t.size());
    shared_basis.resize(shared_t.size() * w);
    for (std::size_t k = 0; k < shared_t.size(); ++k)
      shared_first[k] = eval_basis(p, nu, spec_.closed_u, shared_t[k], &shared_basis[k * w]);
  }
  parallel_for(M, spec_.threads, [&](std::size_t j) {
    const auto row = rows_[j];
    const int n = static_cast<int>(row.size());
    if (shared_u_) {
      std::copy(shared_t.begin(), shared_t.end(), m->u.begin() + off[j]);
      double* G = j == 0 ? m->gram.data() : nullptr;
      Point* R = &m->rhs[j * nu];
      for (int k = 0; k < n; ++k) {
        const int f = shared_first[k];
        const double* b = &shared_basis[static_cast<std::size_t>(k) * w];
        for (int a = 0; a < w; ++a) {
          const int i = wrap_index(f + a, nu);
          R[i] += (1.0 * b[a]) * row[k];
          if (G)
            for (int d = 0; a + d < w; ++d) G[i * w + d] += b[a] * b[a + d];
        }
      }
      return;
    }
    const std::vector<double> t = params(j);
    std::copy(t.begin(), t.end(), m->u.begin() + off[j]);
    const bool gram_here = !shared_u_ || j == 0;
    double* G = gram_here ? &m->gram[(shared_u_ ? 0 : j) * nu * w] : nullptr;
    Point* R = &m->rhs[j * nu];
    std::array<double, kMaxDegree + 1> b;
    // Weighted rows (docs/seams.md): each point's equation scaled by sqrt(w), so its moments
    // by w.
    const auto weights = rows_.row_weights(j);
    for (int k = 0; k < n; ++k) {
      const int f = eval_basis(p, nu, spec_.closed_u, t[k], b.data());
      const double scale = weights.empty() ? 1.0 : std::sqrt(weights[k]);
      if (!weights.empty())
        for (int a = 0; a < w; ++a) b[a] *= scale;
      for (int a = 0; a < w; ++a) {
        const int i = wrap_index(f + a, nu);
        R[i] += (scale * b[a]) * row[k];
        if (G)
          for (int d = 0; a + d < w; ++d) G[i * w + d] += b[a] * b[a + d];
      }
    }
  });
  if (cache_bytes_ + m->bytes() > kMomentBytes) {
    cache_.clear();
    cache_bytes_ = 0;
  }
  cache_bytes_ += m->bytes();
  return *cache_.emplace(nu, std::move(m)).first->second;
}

double TensorProblem::cost(int nu, int nv) const {
  const double n = static_cast<double>(nu) * nv;
  if (shared_u_)  // separable: two banded factorisations and passes over the coefficients
    return 3.0 * (spec_.degree_u + spec_.degree_v + 2) *
           (n + static_cast<double>(nu) * rows_.size());
  return full_cost(spec_, nu, nv);
}

// Rows sharing their u (one G): the least squares separates (Kronecker). With R^T R = G and
// c_j = G^-1 B^T D_j (each row's own fit at nu), sum_j |B (X b_j) - D_j|^2 = sum_j
// |R (X b_j - c_j)|^2 + const = |R (X Bv^T - C)|^2 + const, least for X = C Bv (Bv^T Bv)^-1
// whatever R is: every row's fit, then every column of coefficients fitted across the rows.
bool TensorProblem::solve_separable(int nu, int nv, Surface& out) {
  const Moments& m = moments(nu);
  const int pu = spec_.degree_u, pv = spec_.degree_v, wv = pv + 1;
  const int M = static_cast<int>(rows_.size());
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Upper> gu(
      band_matrix(m.gram.data(), nu, pu + 1, spec_.closed_u));
  if (gu.info() != Eigen::Success) return false;
  Eigen::MatrixXd R(nu, 3 * M);
  for (int j = 0; j < M; ++j)
    for (int i = 0; i < nu; ++i) R.block<1, 3>(i, 3 * j) = m.rhs[j * nu + i].transpose();
  const Eigen::MatrixXd C = gu.solve(R);  // column 3j + a: row j's coefficients, axis a
  const std::vector<double> v = v_at(nv);
  std::vector<double> H(static_cast<std::size_t>(nv) * wv, 0.0);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nv, 3 * nu);
  std::array<double, kMaxDegree + 1> bv;
  for (int j = 0; j < M; ++j) {
    const int fv = eval_basis(pv, nv, spec_.closed_v, v[j], bv.data());
    for (int a = 0; a < wv; ++a) {
      const int l = wrap_index(fv + a, nv);
      for (int d = 0; a + d < wv; ++d) H[l * wv + d] += bv[a] * bv[a + d];
      for (int i = 0; i < nu; ++i)
        for (int x = 0; x < 3; ++x) rhs(l, 3 * i + x) += bv[a] * C(i, 3 * j + x);
    }
  }
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Upper> gv(
      band_matrix(H.data(), nv, wv, spec_.closed_v));
  if (gv.info() != Eigen::Success) return false;
  const Eigen::MatrixXd X = gv.solve(rhs);  // X(l, 3i + a)
  if (!X.allFinite()) return false;
  shape(out, spec_, nu, nv);
  for (int i = 0; i < nu; ++i)
    for (int l = 0; l < nv; ++l)
      out.at(i, l) = Point(X(l, 3 * i), X(l, 3 * i + 1), X(l, 3 * i + 2));
  return true;
}

bool TensorProblem::solve(int nu, int nv, Surface& out) {
  if (shared_u_) return solve_separable(nu, nv, out);
  const Moments& m = moments(nu);
  const int wu = spec_.degree_u + 1;
  const std::vector<double> v = v_at(nv);
  const bool try_cg = tries_cg(spec_, nu, nv, min_points_);
  NormalEquations ne(spec_, nu, nv, try_cg);
  for (std::size_t j = 0; j < rows_.size(); ++j)
    ne.add_row(&m.gram[(shared_u_ ? 0 : j) * nu * wu], &m.rhs[j * nu], v[j]);
  return sfit::detail::solve(ne, try_cg, out);
}

}  // namespace sfit::detail
