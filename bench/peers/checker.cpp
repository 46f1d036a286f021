#include "checker.h"

#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

namespace sfit::peers {

namespace {

struct Domain {
  double u0, u1, v0, v1;
  bool periodic_u, periodic_v;
};

// Parameters sampling one direction: `per_span` samples in each knot span plus the end.
std::vector<double> sample_parameters(const TColStd_Array1OfReal& knots, int per_span) {
  std::vector<double> out;
  for (int i = knots.Lower(); i < knots.Upper(); ++i) {
    const double a = knots(i), b = knots(i + 1);
    for (int s = 0; s < per_span; ++s) out.push_back(a + (b - a) * s / per_span);
  }
  out.push_back(knots(knots.Upper()));
  return out;
}

// Thins `p` to at most `n` values, keeping both ends.
std::vector<double> thin(const std::vector<double>& p, std::size_t n) {
  if (p.size() <= n) return p;
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = p[i * (p.size() - 1) / (n - 1)];
  return out;
}

// Samples of the surface in a uniform 3D hash, for nearest-sample queries.
class SampleHash {
 public:
  SampleHash(const GeomAdaptor_Surface& s, const std::vector<double>& us,
             const std::vector<double>& vs) {
    pts_.reserve(us.size() * vs.size());
    for (double u : us)
      for (double v : vs) {
        pts_.push_back(s.Value(u, v));
        uv_.push_back({u, v});
      }
    gp_XYZ lo = pts_[0].XYZ(), hi = lo;
    for (const gp_Pnt& p : pts_) {
      lo.SetX(std::min(lo.X(), p.X()));
      lo.SetY(std::min(lo.Y(), p.Y()));
      lo.SetZ(std::min(lo.Z(), p.Z()));
      hi.SetX(std::max(hi.X(), p.X()));
      hi.SetY(std::max(hi.Y(), p.Y()));
      hi.SetZ(std::max(hi.Z(), p.Z()));
    }
    lo_ = lo;
    // The samples lie on a surface: about 2 samples per cell along each of its two directions.
    const double diag = (hi - lo).Modulus();
    h_ = std::max(diag * 2.0 / std::sqrt(static_cast<double>(pts_.size())), 1e-300);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(pts_.size());
    for (std::size_t i = 0; i < pts_.size(); ++i) keyed[i] = {key(cell(pts_[i])), i};
    std::sort(keyed.begin(), keyed.end());
    order_.resize(keyed.size());
    for (std::size_t i = 0; i < keyed.size(); ++i) {
      order_[i] = keyed[i].second;
      if (i == 0 || keyed[i].first != keyed[i - 1].first) ranges_[keyed[i].first].first = i;
      ranges_[keyed[i].first].second = i + 1;
    }
  }

  /// Indices of the `k` samples nearest to `p` (fewer if there are fewer samples).
  std::vector<std::uint32_t> nearest(const gp_Pnt& p, std::size_t k) const {
    std::vector<std::pair<double, std::uint32_t>> best;  // sorted by distance, at most k
    auto consider = [&](std::uint32_t s) {
      const double d = pts_[s].SquareDistance(p);
      if (best.size() < k || d < best.back().first) {
        best.insert(std::upper_bound(best.begin(), best.end(), std::make_pair(d, s)), {d, s});
        if (best.size() > k) best.pop_back();
      }
    };
    auto visit = [&](long i, long j, long l) {
      if (i < 0 || j < 0 || l < 0) return;
      auto it = ranges_.find(key({i, j, l}));
      if (it == ranges_.end()) return;
      for (std::size_t q = it->second.first; q < it->second.second; ++q) consider(order_[q]);
    };
    const auto c = cell(p);
    constexpr int kMaxRings = 48;
    bool done = false;
    for (int r = 0; r <= kMaxRings && !done; ++r) {
      // The shell of cells at Chebyshev distance exactly r from p's cell.
      for (long i = c[0] - r; i <= c[0] + r; ++i)
        for (long j = c[1] - r; j <= c[1] + r; ++j) {
          if (std::labs(i - c[0]) == r || std::labs(j - c[1]) == r) {
            for (long l = c[2] - r; l <= c[2] + r; ++l) visit(i, j, l);
          } else {
            visit(i, j, c[2] - r);
            if (r > 0) visit(i, j, c[2] + r);
          }
        }
      // Every cell of ring r+1 is at least r*h away from p.
      done = best.size() == std::min(k, pts_.size()) && best.back().first < (r * h_) * (r * h_);
    }
    if (!done) {  // far from every sample: scan them all
      best.clear();
      for (std::uint32_t s = 0; s < pts_.size(); ++s) consider(s);
    }
    std::vector<std::uint32_t> out;
    for (const auto& b : best) out.push_back(b.second);
    return out;
  }

  std::pair<double, double> uv(std::uint32_t i) const { return uv_[i]; }

 private:
  std::array<long, 3> cell(const gp_Pnt& p) const {
    return {std::lround(std::floor((p.X() - lo_.X()) / h_)),
            std::lround(std::floor((p.Y() - lo_.Y()) / h_)),
            std::lround(std::floor((p.Z() - lo_.Z()) / h_))};
  }
  static std::uint64_t key(const std::array<long, 3>& c) {
    // Points outside the sampled box map to clamped cells; 21 bits per axis.
    auto f = [](long v) { return static_cast<std::uint64_t>(std::clamp(v, 0L, (1L << 21) - 1)); };
    return (f(c[0]) << 42) | (f(c[1]) << 21) | f(c[2]);
  }

  std::vector<gp_Pnt> pts_;
  std::vector<std::pair<double, double>> uv_;
  std::vector<std::uint32_t> order_;
  std::unordered_map<std::uint64_t, std::pair<std::size_t, std::size_t>> ranges_;
  gp_XYZ lo_;
  double h_ = 1;
};

double wrap(double t, double a, double b) {
  const double p = b - a;
  t = std::fmod(t - a, p);
  if (t < 0) t += p;
  return a + t;
}

// Projected Newton from (u, v); returns the smallest distance met and its parameters.
double newton(const GeomAdaptor_Surface& s, const Domain& d, const gp_Pnt& p, double& u,
              double& v) {
  gp_Pnt q;
  gp_Vec su, sv, suu, svv, suv;
  s.D2(u, v, q, su, sv, suu, svv, suv);
  double best = q.SquareDistance(p);
  double bu = u, bv = v;
  for (int it = 0; it < 40; ++it) {
    const gp_Vec r(p, q);  // S - P
    const double gu = r.Dot(su), gv = r.Dot(sv);
    double a = su.Dot(su) + r.Dot(suu), b = su.Dot(sv) + r.Dot(suv), c = sv.Dot(sv) + r.Dot(svv);
    if (!(a > 0 && a * c - b * b > 0)) {  // not a minimum's Hessian: Gauss-Newton instead
      a = su.Dot(su);
      b = su.Dot(sv);
      c = sv.Dot(sv);
    }
    const double reg = 1e-14 * (a + c) + 1e-300;
    a += reg;
    c += reg;
    const double det = a * c - b * b;
    if (!(det > 0)) break;
    double du = -(c * gu - b * gv) / det, dv = -(a * gv - b * gu) / det;
    double step = 1;
    bool improved = false;
    for (int h = 0; h < 30; ++h, step *= 0.5) {
      double nu = u + step * du, nv = v + step * dv;
      nu = d.periodic_u ? wrap(nu, d.u0, d.u1) : std::clamp(nu, d.u0, d.u1);
      nv = d.periodic_v ? wrap(nv, d.v0, d.v1) : std::clamp(nv, d.v0, d.v1);
      gp_Pnt nq;
      gp_Vec nsu, nsv, nsuu, nsvv, nsuv;
      s.D2(nu, nv, nq, nsu, nsv, nsuu, nsvv, nsuv);
      const double nd = nq.SquareDistance(p);
      if (nd < best) {
        const bool small =
            std::abs(nu - u) <= 1e-13 * (d.u1 - d.u0) && std::abs(nv - v) <= 1e-13 * (d.v1 - d.v0);
        u = nu;
        v = nv;
        q = nq;
        su = nsu;
        sv = nsv;
        suu = nsuu;
        svv = nsvv;
        suv = nsuv;
        best = nd;
        bu = u;
        bv = v;
        improved = !small;
        break;
      }
    }
    if (!improved) break;
  }
  u = bu;
  v = bv;
  return std::sqrt(best);
}

}  // namespace

CheckResult check_closest(const Handle(Geom_BSplineSurface) & surface, const Rows& rows,
                          double tolerance, int threads, std::vector<double>* distances) {
  const GeomAdaptor_Surface adaptor(surface);
  Domain dom;
  surface->Bounds(dom.u0, dom.u1, dom.v0, dom.v1);
  dom.periodic_u = surface->IsUPeriodic();
  dom.periodic_v = surface->IsVPeriodic();

  TColStd_Array1OfReal ku(1, surface->NbUKnots()), kv(1, surface->NbVKnots());
  surface->UKnots(ku);
  surface->VKnots(kv);
  std::vector<double> us = sample_parameters(ku, 3), vs = sample_parameters(kv, 3);
  // At most ~4e6 samples, split in proportion to each direction's span count.
  const double limit = 4e6;
  if (static_cast<double>(us.size()) * vs.size() > limit) {
    const double f = std::sqrt(limit / (static_cast<double>(us.size()) * vs.size()));
    us = thin(us, std::max<std::size_t>(8, static_cast<std::size_t>(us.size() * f)));
    vs = thin(vs, std::max<std::size_t>(8, static_cast<std::size_t>(vs.size() * f)));
  }
  const SampleHash hash(adaptor, us, vs);

  const std::size_t m = rows.size();
  struct Partial {
    CheckResult r;
    std::vector<std::size_t> index;  // point index in Rows::points()
    std::vector<double> d;
  };
  threads = std::max(1, threads);
  std::vector<Partial> parts(threads);
  auto work = [&](int t) {
    const GeomAdaptor_Surface s(surface);  // one adaptor (and its span cache) per thread
    CheckResult& r = parts[t].r;
    for (std::size_t j = t; j < m; j += threads) {
      const auto row = rows[j];
      double u = 0, v = 0;
      for (std::size_t k = 0; k < row.size(); ++k) {
        const gp_Pnt p(row[k].x(), row[k].y(), row[k].z());
        if (k == 0) {
          std::tie(u, v) = hash.uv(hash.nearest(p, 1).front());
        }
        double dist = newton(s, dom, p, u, v);
        if (dist > 0.5 * tolerance) {
          ++r.global_searches;
          for (std::uint32_t i : hash.nearest(p, 16)) {
            auto [su, sv] = hash.uv(i);
            const double di = newton(s, dom, p, su, sv);
            if (di < dist) {
              dist = di;
              u = su;
              v = sv;
            }
          }
        }
        parts[t].index.push_back(rows.offsets()[j] + k);
        parts[t].d.push_back(dist);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();

  std::vector<double> dist(rows.total_points(), 0.0);
  for (const Partial& p : parts) {
    for (std::size_t i = 0; i < p.d.size(); ++i) dist[p.index[i]] = p.d[i];
  }
  CheckResult out;
  out.points = dist.size();
  for (const Partial& p : parts) out.global_searches += p.r.global_searches;

  // OpenCASCADE's projection on the points that decide the counts and the maximum.
  std::vector<std::size_t> order(dist.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return dist[a] > dist[b] || (dist[a] == dist[b] && a < b);
  });
  GeomAPI_ProjectPointOnSurf projector;
  projector.Init(surface, dom.u0, dom.u1, dom.v0, dom.v1);
  double refined_max = 0;
  for (std::size_t i : order) {
    if (dist[i] <= tolerance && dist[i] <= refined_max) break;
    const Point& q = rows.points()[i];
    projector.Perform(gp_Pnt(q.x(), q.y(), q.z()));
    ++out.occt_projections;
    if (projector.NbPoints() > 0 && projector.LowerDistance() < dist[i]) {
      dist[i] = projector.LowerDistance();
      ++out.occt_closer;
    }
    refined_max = std::max(refined_max, dist[i]);
  }

  const auto& off = rows.offsets();
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (std::size_t k = off[j]; k < off[j + 1]; ++k) {
      if (dist[k] > tolerance) ++out.out_of_tolerance;
      if (out.worst_row < 0 || dist[k] > out.max_distance) {
        out.max_distance = dist[k];
        out.worst_row = static_cast<long>(j);
        out.worst_index = static_cast<long>(k - off[j]);
      }
    }
  if (distances) *distances = std::move(dist);
  return out;
}

}  // namespace sfit::peers
