// The JSON of the editor's API (docs/editor-api.md): the state it returns and the requests it
// reads. A malformed request throws Error(kUsage) naming the field and what is wrong.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "session.h"
#include "sfit/error.h"

namespace sfit::server {

/// How the surface's control points travel in a state: the contract's nested array; packed
/// exactly ("control_points_f64": base64 of the little-endian doubles, x y z of each point in
/// the order of "control_points", and "control_points_shape" [rows, columns]); or packed for
/// drawing ("control_points_f32": floats of each point less "control_points_origin", the
/// middle of their box, within 1e-7 of the box's size: for a drag step's frame, half the
/// bytes).
enum class Pack { kNone, kF64, kF32 };

/// The state: rows (optional, they are the bulk), surface (the JSON surface contract, its
/// control points as `pack` says), report, whether the surface is final, the deviation
/// against T, options, undo and redo depths.
nlohmann::json state_json(const Session& session, bool with_rows, Pack pack = Pack::kNone);

/// Base64 of `n` bytes.
std::string base64(const unsigned char* data, std::size_t n);
/// The surface contract with its control points packed as `pack` says (kF64 or kF32).
nlohmann::json packed_surface_json(const Surface& s, Pack pack);

/// The fit options as the API shows and takes them.
nlohmann::json options_json(const FitOptions& o);
/// `current` with the fields of `request` changed ({"tolerance": T | [Tx, Ty, Tz],
/// "degree": [p, q], "closed": [u, v], "search": "fast" | "linear", "parameters": name});
/// the library checks the values when it fits. ("phase" is read by phase_of().)
FitOptions options_from_json(const nlohmann::json& request, const FitOptions& current);

/// The "phase" of a request: "once" (absent), "drag", "rest", "end".
MovePhase phase_of(const nlohmann::json& request);

/// Applies one POST /api/edit request to `session`.
void apply_edit(Session& session, const nlohmann::json& request);

/// Parses a request body: an object, or Error(kUsage) saying why not.
nlohmann::json parse_body(const std::string& body);

/// An Error as the API's error object {"error", "code", "place"}.
nlohmann::json error_json(const Error& e);

}  // namespace sfit::server
