// Shared by the libFuzzer targets: what counts as a finding.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "sfit/error.h"

namespace sfit::fuzz {

/// Stops the run as a crash, so libFuzzer saves the input.
[[noreturn]] inline void finding(const char* what) {
  std::fprintf(stderr, "sfit fuzz finding: %s\n", what);
  std::abort();
}

/// An sfit::Error is a proper answer only with one of `allowed` codes and a one-line message.
template <class... Codes>
void check_error(const Error& e, Codes... allowed) {
  if (!((e.code() == allowed) || ...)) {
    std::fprintf(stderr, "unexpected code %s: %s\n", to_string(e.code()), e.what());
    finding("an error with a code this input cannot have");
  }
  if (std::strchr(e.what(), '\n') != nullptr) finding("an error message of more than one line");
}

}  // namespace sfit::fuzz
