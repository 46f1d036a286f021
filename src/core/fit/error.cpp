#include "sfit/error.h"

namespace sfit {

Error::Error(ErrorCode code, const std::string& message, Place place, std::vector<double> values)
    : std::runtime_error(format_error_line(place, message)),
      code_(code),
      message_(message),
      place_(std::move(place)),
      values_(std::move(values)) {}

int Error::exit_code() const noexcept {
  return sfit::exit_code(code_);
}

int exit_code(ErrorCode code) noexcept {
  switch (code) {
    case ErrorCode::kUsage:
      return 2;
    case ErrorCode::kInputUnreadable:
      return 3;
    case ErrorCode::kInputSyntax:
      return 4;
    case ErrorCode::kInputData:
      return 5;
    case ErrorCode::kOutputWrite:
      return 6;
    case ErrorCode::kToleranceNotMet:
      return 7;
    case ErrorCode::kInternal:
      return 8;
    case ErrorCode::kCancelled:
      return 9;
  }
  return 8;
}

const char* to_string(ErrorCode code) noexcept {
  switch (code) {
    case ErrorCode::kUsage:
      return "usage";
    case ErrorCode::kInputUnreadable:
      return "input-unreadable";
    case ErrorCode::kInputSyntax:
      return "input-syntax";
    case ErrorCode::kInputData:
      return "input-data";
    case ErrorCode::kOutputWrite:
      return "output-write";
    case ErrorCode::kToleranceNotMet:
      return "tolerance-not-met";
    case ErrorCode::kInternal:
      return "internal";
    case ErrorCode::kCancelled:
      return "cancelled";
  }
  return "internal";
}

std::string format_error_line(const Place& place, const std::string& message) {
  std::string prefix;
  if (!place.option.empty()) {
    prefix = place.option;
  } else if (!place.file.empty()) {
    prefix = place.file;
    if (place.line >= 0) {
      prefix += ":" + std::to_string(place.line);
      if (place.column >= 0) prefix += ":" + std::to_string(place.column);
    }
  }
  std::string where;
  if (place.row >= 0) {
    where = "row " + std::to_string(place.row);
    if (place.point >= 0) where += ", point " + std::to_string(place.point);
  }
  std::string out;
  if (!prefix.empty()) out = prefix + ": ";
  if (!where.empty()) out += where + ": ";
  out += message;
  // One line, always.
  for (char& c : out)
    if (c == '\n' || c == '\r') c = ' ';
  return out;
}

}  // namespace sfit
