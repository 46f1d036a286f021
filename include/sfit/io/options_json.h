// The option table (sfit/options.h) as JSON: what `sfit options --format json` prints and the
// editor's server serves (GET /api/options-table).
#pragma once

#include <nlohmann/json.hpp>

#include "sfit/options.h"

namespace sfit::io {

/// [{"name", "flag", "group", "type", "default", "min", "max", "choices", "help"}, ...] in the
/// table's order; "default" is null where it depends on the data or another option, "min" and
/// "max" only for integer and number options, "choices" only for choice options.
nlohmann::json option_table_json();

}  // namespace sfit::io
