// The OpenCASCADE side of the section reader (private to sfit_exchange): read_sections()
// runs read_sections_here() in a child process and checks what comes back in the caller.
#pragma once

#include <string>

#include "sfit/exchange/readers.h"

namespace sfit::exchange::detail {

bool is_step_extension(const std::string& e);
bool is_iges_extension(const std::string& e);

/// Reads the curves of `path` with OpenCASCADE in this process, in the file's own length
/// unit. Refuses (Error) a file whose top-level curve entities do not all translate, naming
/// the first that does not. May crash on a hostile file: call it in a child process.
SectionsFile read_sections_here(const std::string& path);

/// The checks of the caller on what was read, as the .rows reader makes them: every row
/// has points, every coordinate finite and within the range sfit computes in (|x| <= 1e150).
void check_sections(const SectionsFile& sections, const std::string& path);

}  // namespace sfit::exchange::detail
