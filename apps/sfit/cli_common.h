// Helpers shared by the sfit subcommands.
#pragma once

#include <string>

#include "sfit/rows.h"
#include "sfit/surface_fit.h"

namespace sfit::cli {

/// Parses "T" or "Tx,Ty,Tz" (each a finite number >= 0); throws Error(kUsage) naming `option`.
Point parse_tolerance(const std::string& text, const std::string& option);

/// Reads input rows by extension (.rows, and whatever the exchange part adds: .csv, .step,
/// .iges); "-" reads .rows from standard input.
struct Input {
  Rows rows;
  std::vector<long> first_line;  ///< line of each row's first point, where the format has lines
  std::string name;
};
Input read_input(const std::string& path);

/// True when messages should be printed (not --quiet).
extern bool verbose;
/// One line to stderr, prefixed "sfit: ".
void say(const std::string& line);

}  // namespace sfit::cli
