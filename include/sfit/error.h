// The one error type of sfit: a code, the place it concerns and the offending values.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace sfit {

/// What went wrong. Each code has its own process exit code (see exit_code()) and its own
/// line in the README section "Errors and exit codes".
enum class ErrorCode {
  kUsage,            ///< an option is unknown, missing, malformed or out of range (exit 2)
  kInputUnreadable,  ///< an input file is missing or cannot be read (exit 3)
  kInputSyntax,      ///< an input file is malformed at file:line:column (exit 4)
  kInputData,        ///< the input parses but cannot be fitted: NaN, empty row, ... (exit 5)
  kOutputWrite,      ///< an output file cannot be written (exit 6)
  kToleranceNotMet,  ///< the surface could not be brought within tolerance (exit 7)
  kInternal,         ///< a bug: an invariant of sfit itself failed (exit 8)
  kCancelled,        ///< the caller stopped the fit (FitOptions::progress, cancel; exit 9)
};

/// Where an error is: any field left at its default is unknown or does not apply.
struct Place {
  std::string file;    ///< input or output path, "-" for standard input
  long line = -1;      ///< 1-based line in `file`
  long column = -1;    ///< 1-based column (byte) in that line
  long row = -1;       ///< 0-based row of points
  long point = -1;     ///< 0-based point inside `row`
  std::string option;  ///< command-line option, e.g. "--tol"
};

/// The exception every sfit function throws for bad input or failure.
class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, const std::string& message, Place place = {},
        std::vector<double> values = {});

  ErrorCode code() const noexcept { return code_; }
  const Place& place() const noexcept { return place_; }
  /// The offending numbers (a coordinate, a tolerance, a degree ...), as given.
  const std::vector<double>& values() const noexcept { return values_; }
  /// The bare message without the place.
  const std::string& message() const noexcept { return message_; }
  /// Process exit code of the CLI for this error.
  int exit_code() const noexcept;

 private:
  ErrorCode code_;
  std::string message_;
  Place place_;
  std::vector<double> values_;
};

/// Exit code of the CLI for `code` (2 ... 9; 0 is success, 1 is never used).
int exit_code(ErrorCode code) noexcept;
/// Short stable name of `code`, e.g. "input-syntax".
const char* to_string(ErrorCode code) noexcept;
/// One line "file:line:column: message" (or "option: message", or "row 3, point 7: message").
std::string format_error_line(const Place& place, const std::string& message);

}  // namespace sfit
