// The section reader's checks that need no OpenCASCADE (section_child.h): the file names it
// takes, and what it read, checked in the caller (never in the child that ran OpenCASCADE).
#include <cstdio>

#include "section_child.h"
#include "sfit/error.h"

namespace sfit::exchange::detail {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& msg, long row) {
  throw Error(ErrorCode::kInputData, msg, Place{.file = path, .row = row});
}

std::string g(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

}  // namespace

bool is_step_extension(const std::string& e) {
  return e == "step" || e == "stp";
}
bool is_iges_extension(const std::string& e) {
  return e == "igs" || e == "iges";
}

void check_sections(const SectionsFile& s, const std::string& path) {
  for (std::size_t j = 0; j < s.rows.size(); ++j) {
    const auto row = s.rows[j];
    const long r = static_cast<long>(j);
    if (row.empty()) fail(path, "curve gives no points", r);
    for (const Point& p : row) {
      if (!p.allFinite()) fail(path, "curve gives a non-finite point", r);
      if (p.cwiseAbs().maxCoeff() > 1e150)
        fail(path,
             "curve reaches (" + g(p.x()) + ", " + g(p.y()) + ", " + g(p.z()) +
                 "), out of the range sfit computes in (|x| <= 1e150)",
             r);
    }
  }
}

}  // namespace sfit::exchange::detail
