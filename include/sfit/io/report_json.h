// The fit report read back from its JSON form (docs/surface-json.md): the inverse of
// report_to_json_text(), so a report travels (a pickled Python Fit) and comes back the same.
#pragma once

#include <string>
#include <string_view>

#include "sfit/surface_fit.h"

namespace sfit::io {

/// Reads a report written by report_to_json_text() (or the "report" of a surface file).
/// report_to_json_text(report_from_json_text(t)) == t for every t sfit wrote; a seam list
/// with no re-ordered row comes back empty ("as given"), which writes the same. Throws
/// Error(kInputSyntax) for malformed JSON, Error(kInputData) naming the key for a missing or
/// mistyped value.
FitReport report_from_json_text(std::string_view text, const std::string& name);

}  // namespace sfit::io
