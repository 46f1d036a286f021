#include "hold.h"

#include <chrono>
#include <string>

#include "api_json.h"
#include "sfit/error.h"

namespace sfit::server {

using nlohmann::json;

namespace {

// `o` with the counts and rule of the fit `r` held, by the method that made it: where the
// surface search kept the two stages' surface, their counts (the search's knots differ, so its
// fixed-count solve may have an empty knot span at that pair).
void hold_at(FitOptions& o, const FitReport& r) {
  o.parametrization = r.parametrization;
  if (r.method == FitMethod::kSurface) {
    o.method = FitMethod::kSurface;
    o.counts = std::array<int, 2>{r.count_u, r.count_v};
  } else {
    o.method = FitMethod::kSfit01;
    o.search = CountSearch::kKnown;
    o.row_count_hints = r.row_counts;
    o.column_count_hints = r.column_counts;
  }
}

void release(FitOptions& o, FitMethod method) {
  o.method = method;
  o.counts.reset();
  if (o.search == CountSearch::kKnown) o.search = CountSearch::kFast;
  o.row_count_hints.clear();
  o.column_count_hints.clear();
}

}  // namespace

bool held(const FitOptions& o) {
  return o.counts.has_value() || o.search == CountSearch::kKnown;
}

FitOptions options_with_hold(const json& body, const Session& session, FitMethod method) {
  json rest = body;
  rest.erase("hold");
  FitOptions o = options_from_json(rest, session.options());
  bool hold = held(session.options());
  if (body.contains("hold")) {
    if (!body["hold"].is_boolean())
      throw Error(ErrorCode::kUsage, "must be true or false", Place{.option = "hold"});
    hold = body["hold"].get<bool>();
  }
  if (!hold) {
    // A method the request names stays; a released hold returns to the session's method.
    release(o, rest.contains("method") || !held(session.options()) ? o.method : method);
  } else if (!held(session.options()) || o.method != FitMethod::kSurface) {
    hold_at(o, session.result().report);  // newly held, or the two stages' counts kept
    if (rest.contains("parameters")) o.parametrization = options_from_json(rest, o).parametrization;
  }
  return o;
}

json search_without_hold(const json& body, const Session& session, FitMethod method) {
  FitOptions o = options_from_json(body, session.options());
  release(o, method);
  const auto t0 = std::chrono::steady_clock::now();
  const FitResult fit = fit_surface(session.rows(), o);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const FitReport& held_report = session.result().report;
  return json{{"counts", {fit.report.count_u, fit.report.count_v}},
              {"within", fit.report.within_tolerance},
              {"parameters", std::string(to_string(fit.report.parametrization))},
              {"held", {held_report.count_u, held_report.count_v}},
              {"seconds", s}};
}

}  // namespace sfit::server
