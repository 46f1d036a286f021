// The surface search's result replaced by a surface below the points, or its report saying
// why not (below_points.h, docs/method.md 7.12).
#include <optional>
#include <string>

#include "below_points.h"
#include "fit_frame.h"
#include "fit_monitor.h"
#include "neighbour_noise.h"
#include "rows_alone.h"
#include "sfit/fold_check.h"

namespace sfit::detail {

bool replace_below_points(const Frame& fr, const FitOptions& o, bool forced, FitResult& r,
                          bool rows_tell) {
  const long points = static_cast<long>(fr.centred.total_points());
  const bool above = static_cast<long>(r.surface.count_u) * r.surface.count_v > points;
  const bool folded = o.fold_guard && r.report.fold > kFoldRelative * fr.box.diagonal();
  if ((!above && !folded) || (o.tolerance.array() == 0).all()) return false;
  // A rule the caller named is kept (the fallback is the geometric rule's): only where sfit
  // chooses the rule (auto, fewest) or the geometric rule was asked for.
  const Parametrization p = o.parametrization;
  if (p != Parametrization::kAuto && p != Parametrization::kFewest &&
      p != Parametrization::kGeometric) {
    if (above)
      r.report.stop_reason +=
          std::string("; more control points than data points under the rule asked for: ") +
          (forced ? "T forces interpolation, the data's noise or its jumps between points exceed T"
                  : "no pair with fewer held T at every point (the default rule may fit below "
                    "the points)");
    return false;
  }
  // Where the rows tell (each row's curve is the surface at its v), what they need alone;
  // where they do not (the geometric rule, searched below a cap because every row needs all
  // its points, gives each point its own v), the points against their neighbours' quadric: no
  // parameter rule enters it.
  std::string rows_need;
  const bool claim =
      forced || (rows_tell ? t_forces_interpolation(fr.centred, o, fr.roundoff, rows_need)
                           : neighbours_force_interpolation(fr.centred, o, fr.roundoff, rows_need));
  if (claim) {
    // What shows it: the rows alone need about every point (noise or jumps beyond T, or, on
    // smooth rows at a tiny T, each row's curve at its own parameters: generated fuselage
    // sections at 1e-6 of the diagonal need 944 of their 1,030 points alone), or the points
    // against their neighbours (noise).
    if (above) {
      r.report.stop_reason += "; more control points than data points: T forces interpolation, ";
      if (rows_need.empty())
        r.report.stop_reason += "the data's noise or its jumps between points exceed T";
      else if (rows_tell)
        r.report.stop_reason += "each row alone needs about every point at T (" + rows_need +
                                "): the data's noise or its jumps exceed T, or T is so small "
                                "that each row's curve at its own parameters needs them";
      else
        r.report.stop_reason += "the data's noise exceeds T (" + rows_need + ")";
    }
    return false;
  }
  progress_phase("below the points", 1);
  std::string why;
  std::optional<GeometricFit> g = fit_below_points(fr, o, points, why);
  progress_advance(1);
  if (!g) {
    // What the rows alone need, over many of them: numbers a user can check against the
    // points (where nearly all are needed, no surface far below the points is in sight).
    const std::string note = rows_alone_note(fr.centred, o, fr.roundoff);
    const std::string need = note.empty() ? rows_need : note;
    if (!above) {
      r.report.stop_reason += "; it folds, and no unfolded surface below the points: " + why +
                              (need.empty() ? "" : "; " + need);
      return false;
    }
    // Jumps beyond T at a minority of the points, spread over the rows and along them (a LiDAR
    // tile's edges and trees): no median tells, yet knot lines are needed about everywhere.
    std::string jumps;
    if (jumps_force_interpolation(fr.centred, o, fr.roundoff, jumps)) {
      r.report.stop_reason +=
          "; more control points than data points: T forces interpolation, the data's jumps "
          "between points exceed T (" +
          jumps + "; the geometric rule below the points: " + why + ")";
      return false;
    }
    // What was measured, under the rules searched (no proof that no surface below the points
    // exists): the search of the row rules gave nothing smaller (its reason comes first), and
    // where each row's curve is the surface at its v, nu follows what the rows need alone
    // (measured at chord length, a proxy: the rules' positions differ); the geometric rule's
    // pairs below the points did not hold.
    r.report.stop_reason +=
        "; more control points than data points: at this T no surface below the points held "
        "under the rules searched (as measured, not a proof that none exists): the row rules' "
        "search gave nothing smaller (as said first)" +
        (note.empty() ? std::string()
                      : " (under a row rule each row's curve is the surface at that row's v, so "
                        "along u it needs about what a row alone needs at its positions; "
                        "measured at chord length: " +
                            note + ")") +
        "; the geometric rule below the points: " + why +
        (note.empty() && !rows_need.empty() ? "; " + rows_need : "");
    return false;
  }
  DeviationCheck c;
  fr.judge(g->surface, g->u, g->v, &c, nullptr, false);
  const long tried = g->tried;
  std::string stop = g->stop + "; in place of " + std::to_string(r.surface.count_u) + " x " +
                     std::to_string(r.surface.count_v) + " (" + r.report.stop_reason + ")";
  FitResult out = assemble_geometric(fr, std::move(*g), c, o);
  FitReport& rep = out.report;
  rep.pairs_tried = r.report.pairs_tried + tried;
  rep.rules_searched = r.report.rules_searched;
  rep.stop_reason = std::move(stop);
  rep.row_counts = std::move(r.report.row_counts);
  rep.column_counts = std::move(r.report.column_counts);
  rep.solves = r.report.solves;
  r = std::move(out);
  return true;
}

}  // namespace sfit::detail
