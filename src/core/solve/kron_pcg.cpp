#include "kron_pcg.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <memory>

namespace sfit::detail {

namespace {

// Relative residual |A x - b| / |b| at which CG stops: the least-squares surface to about
// 1e-11 of its size, far below any tolerance a fit is asked for (round-off is 1e-12 of the
// diagonal, fit_frame.h).
constexpr double kTolerance = 1e-11;
// Iterations before the caller falls back to the factorisation (measured on the shared data
// sets: 8-40 at the chord and centripetal rules; docs/control-points.md).
constexpr int kMaxIterations = 150;

using Llt = Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Upper>;

// P^-1 = (Gbar (x) H_s)^-1 for Eigen's iterative solvers (the interface of its
// DiagonalPreconditioner). The factors are set by the caller through setup().
class KroneckerPreconditioner {
 public:
  using StorageIndex = Eigen::VectorXd::StorageIndex;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic };

  KroneckerPreconditioner() = default;
  template <typename MatType>
  explicit KroneckerPreconditioner(const MatType&) {}

  bool setup(const Eigen::SparseMatrix<double>& Gbar, const Eigen::SparseMatrix<double>& Hs) {
    g_ = std::make_shared<Llt>(Gbar);
    h_ = std::make_shared<Llt>(Hs);
    nu_ = Gbar.rows();
    nv_ = Hs.rows();
    return g_->info() == Eigen::Success && h_->info() == Eigen::Success;
  }
  Eigen::Index rows() const { return nu_ * nv_; }
  Eigen::Index cols() const { return nu_ * nv_; }
  template <typename MatType>
  KroneckerPreconditioner& analyzePattern(const MatType&) {
    return *this;
  }
  template <typename MatType>
  KroneckerPreconditioner& factorize(const MatType&) {
    return *this;
  }
  template <typename MatType>
  KroneckerPreconditioner& compute(const MatType&) {
    return *this;
  }
  template <typename Rhs, typename Dest>
  void _solve_impl(const Rhs& b, Dest& x) const {
    // b(i * nv + l) as R(l, i): Z = H_s^-1 R Gbar^-1 (both symmetric).
    const Eigen::MatrixXd R = Eigen::Map<const Eigen::MatrixXd>(b.derived().data(), nv_, nu_);
    const Eigen::MatrixXd Y = h_->solve(R);
    const Eigen::MatrixXd Zt = g_->solve(Y.transpose());
    x.resize(nu_ * nv_);
    Eigen::Map<Eigen::MatrixXd>(x.data(), nv_, nu_) = Zt.transpose();
  }
  template <typename Rhs>
  const Eigen::Solve<KroneckerPreconditioner, Rhs> solve(const Eigen::MatrixBase<Rhs>& b) const {
    return Eigen::Solve<KroneckerPreconditioner, Rhs>(*this, b.derived());
  }
  Eigen::ComputationInfo info() { return Eigen::Success; }

 private:
  std::shared_ptr<Llt> g_, h_;
  Eigen::Index nu_ = 0, nv_ = 0;
};

}  // namespace

bool solve_kron_pcg(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixX3d& rhs,
                    const Eigen::SparseMatrix<double>& Gbar, const Eigen::SparseMatrix<double>& Hs,
                    Eigen::MatrixX3d& x, int* iterations) {
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Upper, KroneckerPreconditioner> cg;
  if (!cg.preconditioner().setup(Gbar, Hs)) return false;
  cg.setTolerance(kTolerance);
  cg.setMaxIterations(kMaxIterations);
  cg.compute(A);
  x.resize(rhs.rows(), 3);
  int most = 0;
  for (int a = 0; a < 3; ++a) {
    const Eigen::VectorXd b = rhs.col(a);
    if (b.squaredNorm() == 0) {
      x.col(a).setZero();
      continue;
    }
    const Eigen::VectorXd xa = cg.solve(b);
    most = std::max(most, static_cast<int>(cg.iterations()));
    if (cg.info() != Eigen::Success) return false;
    x.col(a) = xa;
  }
  if (iterations) *iterations = most;
  return true;
}

}  // namespace sfit::detail
