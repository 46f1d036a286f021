// Holding the surface's shape of control points while sculpting (docs/editor.md, "Calm
// sculpting"): with the hold on, every refit (drag steps, the hand at rest, typed edits) keeps
// the counts (nu, nv) and the parameter rule of the surface shown when the hold was set, so a
// moved point changes the surface near it and no more; the full count search runs only on
// request (search_without_hold) and replaces the surface only once the hold is released.
#pragma once

#include <nlohmann/json.hpp>

#include "session.h"

namespace sfit::server {

/// The options of a POST /api/options request `body` applied to the session's: as
/// options_from_json(), and "hold": true fixes the counts and the rule of the current full
/// fit (FitOptions::counts; where the two stages made it: their counts as the answer),
/// "hold": false frees them (the search again, by `method`, the session's own method). A
/// request without "hold" keeps the current hold.
FitOptions options_with_hold(const nlohmann::json& body, const Session& session,
                             FitMethod method = FitMethod::kSurface);

/// True when `o` holds the counts (set by options_with_hold).
bool held(const FitOptions& o);

/// What the full count search gives for the session's current rows without the hold (the
/// session is not changed): {"counts": [nu, nv], "within": bool, "parameters": rule,
/// "held": [nu, nv] of the shown surface, "seconds": s}. `body` may name "parameters" (the
/// rule to search with; default: the session's).
nlohmann::json search_without_hold(const nlohmann::json& body, const Session& session,
                                   FitMethod method = FitMethod::kSurface);

}  // namespace sfit::server
