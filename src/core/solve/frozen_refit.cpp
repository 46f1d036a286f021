#include "sfit/frozen_refit.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "scattered_lsq.h"
#include "sfit/error.h"
#include "sfit/fit_check.h"
#include "sfit/surface_eval.h"

namespace sfit {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The weight of the smoothness term (the control net's second differences along u and v, the
// scattered least squares' own: scattered_lsq.h) relative to the data term's mean diagonal: it
// only decides control points that no data point determines (a knot span without data), where
// the system would be singular, and moves the others by about this fraction of T's scale, far
// below the check's resolution.
constexpr double kFrozenSmoothing = 1e-8;

}  // namespace

struct FrozenRefit::Impl {
  FitResult at;  // the full fit the drag starts from: surface (template), u, v, report
  std::vector<std::size_t> offsets;
  Point centre = Point::Zero();
  int p = 0, q = 0, nu = 0, nv = 0;
  std::vector<int> fu, fv;     // per point: first control point along u, v (distinct index)
  std::vector<double> bu, bv;  // per point: p + 1, q + 1 basis values
  // The general case: the scattered least squares' banded Cholesky of the data term plus its
  // smoothness term (scattered_lsq.h), factorised once.
  detail::ScatteredFactor factor;
  // Rows of one length and one v each, most sharing their u (a grid at the uniform or paper
  // rule, a few rows edited): N = N0 + P E P^T, where N0 = Gu (x) Gv is the Kronecker product of
  // the shared rows' Gram matrix Gu and the rows' Gram matrix Gv (control point i * nv + j),
  // and E, on the control points P of the columns J the other rows touch, their Gram matrices'
  // difference from Gu. N0 x = r is X = Gu^-1 R Gv^-1 (R, X as nu x nv matrices), and N^-1 by
  // Woodbury: N^-1 = N0^-1 - N0^-1 P (I + E K)^-1 E P^T N0^-1, K = P^T N0^-1 P =
  // Gu^-1 (x) Gv^-1[J, J]. Two small factorisations and one of nu |J| unknowns instead of one
  // of nu nv (0.6-1.6 s at 94 x 96 control points, load 6-10).
  bool separable = false;
  Eigen::LLT<Eigen::MatrixXd> gu, gv;
  std::vector<int> cols;                     // J
  Eigen::MatrixXd e;                         // E, (a, i) -> a * nu + i for column cols[a]
  Eigen::PartialPivLU<Eigen::MatrixXd> cap;  // I + E K
  bool make_separable(const Rows& rows, const FitResult& at);

  // N0^-1 rhs (one column of nu nv).
  Eigen::VectorXd solve0(const Eigen::VectorXd& rhs) const {
    using Grid = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const Grid r = Eigen::Map<const Grid>(rhs.data(), nu, nv);
    const Grid x = gv.solve(gu.solve(r).transpose()).transpose();
    Eigen::VectorXd out(rhs.size());
    Eigen::Map<Grid>(out.data(), nu, nv) = x;
    return out;
  }
  // N^-1 rhs, column by column (rhs: nu nv rows, control point i * nv + j).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const {
    if (!separable) {
      Eigen::MatrixXd out = rhs;
      std::vector<double> x(static_cast<std::size_t>(rhs.rows()));
      for (Eigen::Index a = 0; a < rhs.cols(); ++a) {
        Eigen::VectorXd::Map(x.data(), rhs.rows()) = rhs.col(a);
        factor.solve(x);
        out.col(a) = Eigen::VectorXd::Map(x.data(), rhs.rows());
      }
      return out;
    }
    Eigen::MatrixXd out(rhs.rows(), rhs.cols());
    const Eigen::Index m = static_cast<Eigen::Index>(cols.size()) * nu;
    for (Eigen::Index a = 0; a < rhs.cols(); ++a) {
      Eigen::VectorXd x = solve0(rhs.col(a));
      if (m > 0) {
        Eigen::VectorXd z(m);
        for (std::size_t c = 0; c < cols.size(); ++c)
          for (int i = 0; i < nu; ++i) z[c * nu + i] = x[i * nv + cols[c]];
        const Eigen::VectorXd w = cap.solve(e * z);
        Eigen::VectorXd pw = Eigen::VectorXd::Zero(x.size());
        for (std::size_t c = 0; c < cols.size(); ++c)
          for (int i = 0; i < nu; ++i) pw[i * nv + cols[c]] = w[c * nu + i];
        x -= solve0(pw);
      }
      out.col(a) = x;
    }
    return out;
  }

  // Calls f(c, w) for the (p + 1)(q + 1) control points c point m's equation touches.
  template <class F>
  void each(std::size_t m, F&& f) const {
    const double* a = &bu[m * (p + 1)];
    const double* b = &bv[m * (q + 1)];
    for (int x = 0; x <= p; ++x) {
      const int i = (fu[m] + x) % nu;
      for (int y = 0; y <= q; ++y) f(i * nv + (fv[m] + y) % nv, a[x] * b[y]);
    }
  }
};

// The Kronecker case (separable): every row of one length, one v per row, the u shared by the
// most rows, the others touching at most kMaxColumns columns of control points, and the
// factors sound (every span has data); false where not.
bool FrozenRefit::Impl::make_separable(const Rows& rows, const FitResult& at) {
  // Bounds on the dense work: Gu, Gv inverted (nu^3, nv^3) and I + E K factorised
  // (nu |J|)^3; beyond them the general case's banded factorisation.
  constexpr int kMaxColumns = 12, kMaxCount = 500, kMaxCorrection = 800;
  Impl& m = *this;
  const std::size_t len = rows[0].size(), nrows = rows.size();
  if (!at.v_points.empty() || std::max(m.nu, m.nv) > kMaxCount) return false;
  for (std::size_t j = 0; j < nrows; ++j)
    if (rows[j].size() != len) return false;
  const auto same = [&](std::size_t a, std::size_t b) {
    for (std::size_t k = 0; k < len; ++k)
      if (at.u[m.offsets[a] + k] != at.u[m.offsets[b] + k]) return false;
    return true;
  };
  // The shared u: that of the first row that most rows of the first few share.
  std::size_t base = 0, most = 0;
  for (std::size_t a = 0; a < std::min<std::size_t>(nrows, 4); ++a) {
    std::size_t n = 0;
    for (std::size_t j = 0; j < nrows; ++j) n += same(a, j);
    if (n > most) most = n, base = a;
  }
  // The Gram matrix of one row's u.
  const auto gram = [&](std::size_t row) {
    Eigen::MatrixXd g = Eigen::MatrixXd::Zero(m.nu, m.nu);
    for (std::size_t k = m.offsets[row]; k < m.offsets[row] + len; ++k)
      for (int x = 0; x <= m.p; ++x)
        for (int x2 = 0; x2 <= m.p; ++x2)
          g((m.fu[k] + x) % m.nu, (m.fu[k] + x2) % m.nu) +=
              m.bu[k * (m.p + 1) + x] * m.bu[k * (m.p + 1) + x2];
    return g;
  };
  std::vector<std::size_t> other;
  std::vector<int> cols_of;
  for (std::size_t j = 0; j < nrows; ++j) {
    if (same(base, j)) continue;
    other.push_back(j);
    for (int y = 0; y <= m.q; ++y) cols_of.push_back((m.fv[m.offsets[j]] + y) % m.nv);
  }
  std::sort(cols_of.begin(), cols_of.end());
  cols_of.erase(std::unique(cols_of.begin(), cols_of.end()), cols_of.end());
  if (cols_of.size() > static_cast<std::size_t>(kMaxColumns) ||
      static_cast<long>(cols_of.size()) * m.nu > kMaxCorrection)
    return false;
  const Eigen::MatrixXd gu0 = gram(base);
  Eigen::MatrixXd gv0 = Eigen::MatrixXd::Zero(m.nv, m.nv);
  for (std::size_t j = 0; j < nrows; ++j) {
    const std::size_t k = m.offsets[j];  // the row's v: that of its first point
    for (int y = 0; y <= m.q; ++y)
      for (int y2 = 0; y2 <= m.q; ++y2)
        gv0((m.fv[k] + y) % m.nv, (m.fv[k] + y2) % m.nv) +=
            m.bv[k * (m.q + 1) + y] * m.bv[k * (m.q + 1) + y2];
  }
  m.gu.compute(gu0);
  m.gv.compute(gv0);
  if (m.gu.info() != Eigen::Success || m.gv.info() != Eigen::Success) return false;
  // A positive pivot may still be round-off: each factor must reproduce its matrix's identity.
  const auto sound = [](const Eigen::MatrixXd& g, const Eigen::MatrixXd& inverse) {
    const Eigen::MatrixXd i = Eigen::MatrixXd::Identity(g.rows(), g.cols());
    return (g * inverse - i).cwiseAbs().maxCoeff() <= 1e-8;
  };
  const Eigen::MatrixXd iu = m.gu.solve(Eigen::MatrixXd::Identity(m.nu, m.nu));
  const Eigen::MatrixXd iv = m.gv.solve(Eigen::MatrixXd::Identity(m.nv, m.nv));
  if (!sound(gu0, iu) || !sound(gv0, iv)) return false;
  m.cols = cols_of;
  const Eigen::Index nc = static_cast<Eigen::Index>(cols_of.size()), mm = nc * m.nu;
  if (mm > 0) {
    const auto at_col = [&](int c) {
      return static_cast<Eigen::Index>(std::lower_bound(cols_of.begin(), cols_of.end(), c) -
                                       cols_of.begin());
    };
    m.e = Eigen::MatrixXd::Zero(mm, mm);
    for (std::size_t j : other) {
      const Eigen::MatrixXd d = gram(j) - gu0;
      const std::size_t k = m.offsets[j];
      for (int y = 0; y <= m.q; ++y)
        for (int y2 = 0; y2 <= m.q; ++y2) {
          const double w = m.bv[k * (m.q + 1) + y] * m.bv[k * (m.q + 1) + y2];
          const Eigen::Index a = at_col((m.fv[k] + y) % m.nv), b = at_col((m.fv[k] + y2) % m.nv);
          m.e.block(a * m.nu, b * m.nu, m.nu, m.nu) += w * d;
        }
    }
    Eigen::MatrixXd k(mm, mm);
    for (Eigen::Index a = 0; a < nc; ++a)
      for (Eigen::Index b = 0; b < nc; ++b)
        k.block(a * m.nu, b * m.nu, m.nu, m.nu) = iv(cols_of[a], cols_of[b]) * iu;
    const Eigen::MatrixXd c = Eigen::MatrixXd::Identity(mm, mm) + m.e * k;
    m.cap.compute(c);
    // Sound where it solves a system of known answer (one column of ones) to 1e-8.
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(mm);
    if (!((m.cap.solve(c * ones) - ones).cwiseAbs().maxCoeff() <= 1e-8)) return false;
  }
  m.separable = true;
  return true;
}

FrozenRefit::FrozenRefit(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
FrozenRefit::~FrozenRefit() = default;

std::shared_ptr<const FrozenRefit> FrozenRefit::make(const Rows& rows, const FitResult& at,
                                                     std::string& why) {
  const auto t0 = std::chrono::steady_clock::now();
  const Surface& s = at.surface;
  const std::size_t n = static_cast<std::size_t>(s.count_u) * s.count_v;
  if (rows.weighted()) {
    why = "weighted rows";
    return nullptr;
  }
  if (n > kMaxUnknowns) {
    why = std::to_string(s.count_u) + " x " + std::to_string(s.count_v) +
          " control points: more than the frozen refit factorises (" +
          std::to_string(kMaxUnknowns) + ")";
    return nullptr;
  }
  const std::size_t total = rows.total_points();
  if (at.u.size() != total ||
      (at.v_points.empty() ? at.v.size() != rows.size() : at.v_points.size() != total)) {
    why = "the fit's parameters do not match the rows";
    return nullptr;
  }
  auto im = std::make_unique<Impl>();
  Impl& m = *im;
  m.at = at;
  m.offsets = rows.offsets();
  m.p = s.degree_u;
  m.q = s.degree_v;
  m.nu = s.count_u;
  m.nv = s.count_v;
  const BoundingBox box = bounding_box(rows);
  m.centre = 0.5 * (box.min + box.max);
  std::vector<double> vp(total);
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (std::size_t k = m.offsets[j]; k < m.offsets[j + 1]; ++k) vp[k] = at.point_v(j, k);
  const DirectionBasis du = direction_basis(s, true, at.u, 0);
  const DirectionBasis dv = direction_basis(s, false, vp, 0);
  m.fu.resize(total);
  m.fv.resize(total);
  for (std::size_t k = 0; k < total; ++k) {
    m.fu[k] = du.first[k] % m.nu;
    m.fv[k] = dv.first[k] % m.nv;
  }
  m.bu = du.d;
  m.bv = dv.d;

  // The fit's own check, at these parameters: a fit made on reordered rows (seams aligned,
  // rows reversed) does not reproduce it, and its parameters are not the rows'.
  const std::vector<Point>& pts = rows.points();
  Point worst = Point::Zero();
  for (std::size_t k = 0; k < total; ++k) {
    Point sk = Point::Zero();
    m.each(k, [&](int c, double w) { sk += w * s.control[c]; });
    worst = worst.cwiseMax((sk - pts[k]).cwiseAbs());
  }
  const double scale = std::max(box.diagonal(), 1e-300);
  if (!((worst - at.report.max_deviation).cwiseAbs().maxCoeff() <=
        1e-3 * at.report.tolerance.maxCoeff() + 1e-9 * scale)) {
    why =
        "the fit's parameters do not reproduce its check (rows reordered: seams aligned or "
        "rows reversed)";
    return nullptr;
  }

  if (m.make_separable(rows, at)) {
    auto out = std::shared_ptr<FrozenRefit>(new FrozenRefit(std::move(im)));
    out->seconds_ = seconds_since(t0);
    return out;
  }

  // The normal equations (data term plus the smoothness term), the scattered least squares'
  // assembly at these bases and its banded factorisation.
  const detail::ScatteredSpec spec{m.p, m.q, s.periodic_u, s.periodic_v, 1};
  std::vector<double> band(n * (2 * m.p + 1) * (2 * m.q + 1), 0.0);
  std::vector<Point> unused;
  detail::scattered_add_basis(spec, m.nu, m.nv, {}, m.fu, m.bu, m.fv, m.bv, band, unused);
  if (!m.factor.factor(spec, m.nu, m.nv, band, kFrozenSmoothing)) {
    why = s.periodic_u && s.periodic_v
              ? "a surface closed both ways (the frozen refit's band does not take it)"
              : "the frozen normal equations are singular";
    return nullptr;
  }
  auto out = std::shared_ptr<FrozenRefit>(new FrozenRefit(std::move(im)));
  out->seconds_ = seconds_since(t0);
  return out;
}

FitResult FrozenRefit::refit(const Rows& rows) const {
  const auto t0 = std::chrono::steady_clock::now();
  const Impl& m = *impl_;
  const std::size_t n = static_cast<std::size_t>(m.nu) * m.nv;
  if (rows.size() + 1 != m.offsets.size() || rows.offsets() != m.offsets)
    throw Error(ErrorCode::kUsage,
                "the frozen refit takes rows of the sizes of its fit (" +
                    std::to_string(m.offsets.size() - 1) + " rows, " +
                    std::to_string(m.offsets.back()) + " points); got " +
                    std::to_string(rows.size()) + " rows, " + std::to_string(rows.total_points()) +
                    " points",
                Place{}, {static_cast<double>(rows.size())});
  const std::vector<Point>& pts = rows.points();
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(static_cast<Eigen::Index>(n), 3);
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const Eigen::RowVector3d d = (pts[k] - m.centre).transpose();
    m.each(k, [&](int c, double w) { rhs.row(c) += w * d; });
  }
  const Eigen::MatrixX3d x = m.solve(rhs);
  FitResult out;
  out.surface = m.at.surface;
  for (std::size_t c = 0; c < n; ++c)
    out.surface.control[c] = x.row(static_cast<Eigen::Index>(c)).transpose() + m.centre;
  out.u = m.at.u;
  out.v = m.at.v;
  out.v_points = m.at.v_points;
  FitReport& r = out.report;
  r = m.at.report;
  // The library's final check, the one every fit's report gets: the surface as it stands
  // against the drag's rows, allowing for the round-off of evaluating it (fit_check.h).
  check_fit_as_written(out, rows, r.tolerance);
  r.norm = FitNorm::kL2;
  r.pairs_tried = 0;
  r.solves = 1;
  // The shape measures (fold, box excursion, row gap) are not measured again at every step:
  // the report keeps those of the full fit the drag started from, and says so.
  r.stop_reason =
      "quick refit: counts, knots and parameters frozen for the drag; shape measures of the "
      "full fit at its start";
  r.seconds = seconds_since(t0);
  return out;
}

std::vector<double> FrozenRefit::influence(std::size_t row, std::size_t index) const {
  const Impl& m = *impl_;
  const std::size_t n = static_cast<std::size_t>(m.nu) * m.nv;
  if (row + 1 >= m.offsets.size() || index >= m.offsets[row + 1] - m.offsets[row])
    throw Error(ErrorCode::kUsage,
                "no point " + std::to_string(index) + " in row " + std::to_string(row) +
                    " of the frozen refit's rows",
                Place{.row = static_cast<long>(row), .point = static_cast<long>(index)});
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
  m.each(m.offsets[row] + index, [&](int c, double w) { rhs[c] += w; });
  const Eigen::VectorXd g = m.solve(rhs);
  return {g.data(), g.data() + g.size()};
}

}  // namespace sfit
