// The seam hook of the fit (aligned_fit.h, docs/seams.md).
#include "aligned_fit.h"

namespace sfit::detail {

RowAlignment alignment_for(const Rows& rows, const FitOptions& o) {
  return align_rows(rows, o.closed_u, o.seam, o.orient, o.parametrization);
}

std::vector<double> seam_offsets(const RowAlignment& a, bool closed_u) {
  std::vector<double> out;
  if (!closed_u) return out;
  for (const RowSeam& s : a.rows)
    if (s.offset != 0) {
      for (const RowSeam& t : a.rows) out.push_back(t.offset);
      break;
    }
  return out;
}

void shift_positions(std::vector<double>& f, double offset) {
  const std::size_t n = f.size();
  if (offset == 0 || n < 2) return;
  const double start = offset > 0 ? offset * f[1] : offset * (1 - f[n - 1]);
  for (double& x : f) {
    x -= start;
    if (x < 0) x += 1;
    if (x >= 1) x -= 1;
  }
}

void restore_original_order(FitResult& fit, const Rows& original, const RowAlignment& a) {
  const std::vector<std::size_t> idx = original_indices(original, a);
  std::vector<double> u(fit.u.size());
  for (std::size_t k = 0; k < idx.size(); ++k) u[idx[k]] = fit.u[k];
  fit.u = std::move(u);
  if (!fit.v_points.empty()) {  // Parametrization::kGeometric: v per point, likewise
    std::vector<double> v(fit.v_points.size());
    for (std::size_t k = 0; k < idx.size(); ++k) v[idx[k]] = fit.v_points[k];
    fit.v_points = std::move(v);
  }
  FitReport& r = fit.report;
  if (r.worst_row >= 0 && r.worst_index >= 0) {
    const std::size_t j = static_cast<std::size_t>(r.worst_row);
    r.worst_index = static_cast<long>(
        source_index(a.rows[j], original[j].size(), static_cast<std::size_t>(r.worst_index)));
  }
  // A method that moved the seams itself (corner knots on closed rows: u = 0 at a corner) set
  // them on the aligned rows; composed with the alignment, they name original points.
  std::vector<RowSeam> seams = a.rows;
  if (r.seams.size() == seams.size())
    for (std::size_t j = 0; j < seams.size(); ++j) {
      const long n = static_cast<long>(original[j].size()), k = r.seams[j].shift;
      RowSeam& s = seams[j];
      s.shift = ((s.reversed ? s.shift - k : s.shift + k) % n + n) % n;
      s.offset = r.seams[j].offset;
    }
  r.seams = std::move(seams);
}

}  // namespace sfit::detail
