// The surface and report JSON of docs/surface-json.md as nlohmann::json values: for code
// inside this repository that builds bigger JSON documents (the CLI, the editor's server, the
// Python module, tests). Private: the installed header sfit/io/surface_json.h offers the same
// as text, so that no public header needs nlohmann/json.hpp.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "sfit/io/surface_json.h"

namespace sfit::io {

/// The surface in the contract's form: full knot vectors, full control arrays (a periodic
/// direction stores its wrap copies), `periodic` flags. Doubles round-trip exactly.
nlohmann::json surface_to_json(const Surface& surface);
/// surface_to_json() without the control points (for a caller that writes them its own way).
nlohmann::json surface_header_to_json(const Surface& surface);

/// The report keys of the contract plus sfit's extras (degree, closed, column_counts,
/// raised/repaired counts, solves).
nlohmann::json report_to_json(const FitReport& report);

/// Reads a surface in the contract's form; `name` is used in messages.
/// Throws Error(kInputSyntax) for malformed JSON and Error(kInputData) for a surface that
/// breaks the contract (knot vector lengths, knots that decrease, repeat more than the degree
/// or (open) lack degree + 1 equal end knots, a periodic vector whose spacing does not repeat, a
/// periodic direction whose wrap copies differ, non-finite numbers).
Surface surface_from_json(const nlohmann::json& j, const std::string& name);

/// Parses a JSON file with the readers' errors: kInputUnreadable (missing, unreadable, a
/// folder), kInputSyntax (malformed JSON, with nlohmann's line and column), kInputData (a
/// number out of the range of a double, e.g. 1e999).
nlohmann::json read_json_file(const std::string& path);

}  // namespace sfit::io
