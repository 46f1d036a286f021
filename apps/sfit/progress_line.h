// The fit's progress line on a terminal and its stop on SIGINT/SIGTERM (cmd_fit.cpp).
#pragma once

#include <atomic>
#include <string>

#include "sfit/progress.h"

namespace sfit::cli {

/// While alive, SIGINT and SIGTERM set a flag (given to FitOptions::cancel) instead of
/// killing the process, so the fit stops at its next check and nothing is written. A second
/// signal while the first is being honoured kills the process as before (the default action).
class Interruption {
 public:
  Interruption();
  ~Interruption();
  Interruption(const Interruption&) = delete;
  Interruption& operator=(const Interruption&) = delete;

  /// The flag for FitOptions::cancel.
  const std::atomic<bool>* flag() const;
  /// The signal received (SIGINT, SIGTERM), 0 if none.
  int signal() const;
  /// The exit code for it: 128 + the signal's number (130, 143).
  int exit_code() const { return 128 + signal(); }
  /// "interrupted by SIGINT".
  std::string what() const;
};

/// A one-line progress report on standard error, overwritten in place: shown only when
/// standard error is a terminal, after the fit has run `after` seconds; clear() removes it.
class ProgressLine {
 public:
  explicit ProgressLine(bool enabled, double after = 1.0);
  ~ProgressLine() { clear(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// For FitOptions::progress; returns false once `interrupt` has caught a signal.
  ProgressFunction function(const Interruption& interrupt);
  void clear();

 private:
  bool enabled_;
  double after_;
  double last_ = -1;  // seconds of the last line drawn
  bool shown_ = false;
};

}  // namespace sfit::cli
