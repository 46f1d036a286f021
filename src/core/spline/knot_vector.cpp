#include "sfit/knot_vector.h"

#include <algorithm>
#include <cmath>

#include "basis.h"
#include "knots.h"
#include "sfit/error.h"

namespace sfit {
namespace {

[[noreturn]] void bad(const std::string& what, const std::string& why,
                      std::vector<double> values = {}) {
  throw Error(ErrorCode::kInputData, what + ": " + why, Place{.option = what}, std::move(values));
}

bool near_uniform(const std::vector<double>& full, int degree, int count, bool periodic) {
  const std::vector<double> u =
      periodic ? periodic_uniform_knots(degree, count) : clamped_uniform_knots(degree, count);
  if (u.size() != full.size()) return false;
  for (std::size_t i = 0; i < u.size(); ++i)
    if (!(std::abs(full[i] - u[i]) <= 1e-9 * (1 + std::abs(u[i])))) return false;
  return true;
}

}  // namespace

KnotVector KnotVector::from_full(int degree, bool periodic, std::vector<double> full,
                                 const std::string& what) {
  if (degree < 1 || degree > kMaxDegree)
    bad(what, "degree must be 1 ... " + std::to_string(kMaxDegree), {double(degree)});
  const int n = static_cast<int>(full.size());
  const int count = periodic ? n - 2 * degree - 1 : n - degree - 1;
  if (count < degree + 1)
    bad(what, "too few knots for degree " + std::to_string(degree) + " (" + std::to_string(n) + ")",
        {double(n)});
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(full[i])) bad(what, "entry " + std::to_string(i) + " is not finite");
    if (i > 0 && full[i] < full[i - 1])
      bad(what, "entry " + std::to_string(i) + " decreases", {full[i - 1], full[i]});
  }
  // The domain begins at 0 (a shift of the parameter, the same surface).
  if (const double a = full[degree]; a != 0)
    for (double& k : full) k -= a;
  const double end = full[periodic ? degree + count : count];
  if (!(end > 0)) bad(what, "the domain is empty", {end});
  // Multiplicities: the ends of an open vector exactly degree + 1, every other knot <= degree.
  for (int i = 0; i < n;) {
    int j = i;
    while (j < n && full[j] == full[i]) ++j;
    const int m = j - i;
    const bool end_knot = !periodic && (i == 0 || j == n);
    if (end_knot && m != degree + 1)
      bad(what, "an open vector needs " + std::to_string(degree + 1) + " equal knots at each end",
          {full[i], double(m)});
    if (!end_knot && m > degree)
      bad(what,
          "knot " + std::to_string(full[i]) + " repeats " + std::to_string(m) +
              " times (at most the degree, " + std::to_string(degree) + ")",
          {full[i], double(m)});
    i = j;
  }
  if (periodic)
    for (int i = 0; i + count < n; ++i)
      if (!(std::abs(full[i + count] - full[i] - end) <= 1e-9 * end))
        bad(what,
            "a periodic vector repeats its spacing with the period (entry " +
                std::to_string(i + count) + ")",
            {full[i], full[i + count], end});
  KnotVector k;
  k.degree_ = degree;
  k.periodic_ = periodic;
  k.count_ = count;
  if (near_uniform(full, degree, count, periodic)) {
    k.end_ = domain_end(degree, count, periodic);
    return k;
  }
  k.end_ = end;
  k.full_ = std::move(full);
  return k;
}

KnotVector KnotVector::from_breaks(int degree, bool periodic, std::span<const double> breaks,
                                   std::span<const int> mults) {
  const std::string what = "knots";
  const std::size_t m = breaks.size();
  if (m < 2 || breaks[0] != 0) bad(what, "breakpoints must begin at 0 and have an end");
  for (std::size_t i = 1; i < m; ++i)
    if (!(breaks[i] > breaks[i - 1])) bad(what, "breakpoints must increase", {breaks[i]});
  const std::size_t want = periodic ? m - 1 : m - 2;
  if (!mults.empty() && mults.size() != want)
    bad(what, "one multiplicity per " + std::string(periodic ? "" : "interior ") + "breakpoint");
  auto mult = [&](std::size_t i) {  // breakpoint i's multiplicity (i < m - 1)
    const int r = mults.empty() ? 1 : mults[periodic ? i : i - 1];
    if (r < 1 || r > degree) bad(what, "multiplicities must be 1 ... degree", {double(r)});
    return r;
  };
  std::vector<double> full;
  if (!periodic) {
    full.assign(static_cast<std::size_t>(degree + 1), 0.0);
    for (std::size_t i = 1; i + 1 < m; ++i) full.insert(full.end(), mult(i), breaks[i]);
    full.insert(full.end(), static_cast<std::size_t>(degree + 1), breaks[m - 1]);
    return from_full(degree, false, std::move(full), what);
  }
  std::vector<double> one;  // the knots of one period [0, P)
  for (std::size_t i = 0; i + 1 < m; ++i) one.insert(one.end(), mult(i), breaks[i]);
  const int count = static_cast<int>(one.size());
  const double period = breaks[m - 1];
  for (int k = 0; k < count + 2 * degree + 1; ++k) {
    const int idx = k - degree;
    const int q = idx >= 0 ? idx / count : -((-idx + count - 1) / count);
    full.push_back(one[static_cast<std::size_t>(idx - q * count)] + q * period);
  }
  return from_full(degree, true, std::move(full), what);
}

void KnotVector::breaks(std::vector<double>& values, std::vector<int>& mults) const {
  values.clear();
  mults.clear();
  const int lo = periodic_ ? degree_ : 0;
  const int hi = periodic_ ? degree_ + count_ : static_cast<int>(full_.size()) - 1;
  for (int i = lo; i <= hi; ++i) {
    if (!values.empty() && full_[i] == values.back()) {
      ++mults.back();
      continue;
    }
    values.push_back(full_[i]);
    mults.push_back(1);
  }
  if (periodic_) {  // the period's end carries its start's multiplicity
    mults.back() = mults.front();
  }
}

int KnotVector::find_span(double& t) const {
  // The domain's knots: [knots[degree], knots[degree + count]] periodic, [knots[degree],
  // knots[count]] open (whose last degree + 1 knots are equal).
  const int hi = periodic_ ? degree_ + count_ : count_;
  if (periodic_) {
    if (!(t >= 0 && t < end_)) {
      t = std::fmod(t, end_);
      if (t < 0) t += end_;
      if (!(t >= 0) || t >= end_) t = 0;  // NaN, round-off at the seam
    }
  } else {
    if (!(t > 0)) t = 0;
    if (t > end_) t = end_;
  }
  const auto first = full_.begin() + degree_, last = full_.begin() + hi + 1;
  int s = static_cast<int>(std::upper_bound(first, last, t) - full_.begin()) - 1;
  if (s > hi - 1) s = hi - 1;  // t at the open end: the last non-empty span
  return s;
}

std::vector<double> full_knots(const KnotVector& k, int degree, int count, bool periodic) {
  if (!k.uniform()) return k.full();
  return periodic ? periodic_uniform_knots(degree, count) : clamped_uniform_knots(degree, count);
}

}  // namespace sfit
