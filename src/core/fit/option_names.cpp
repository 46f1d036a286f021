#include "sfit/option_names.h"

#include <cmath>
#include <sstream>

#include "parse_name.h"
#include "sfit/error.h"

namespace sfit {

std::string_view to_string(CountSearch search) {
  switch (search) {
    case CountSearch::kLinear:
      return "linear";
    case CountSearch::kFast:
      return "fast";
    case CountSearch::kKnown:
      return "known";
  }
  return "fast";
}

bool parse_count_search(std::string_view name, CountSearch& out) {
  return detail::parse_name(name, {CountSearch::kFast, CountSearch::kLinear, CountSearch::kKnown},
                            out);
}

bool parse_closed(std::string_view name, bool& closed_u, bool& closed_v) {
  if (name.empty() || name == "none") {
    closed_u = closed_v = false;
  } else if (name == "u") {
    closed_u = true;
    closed_v = false;
  } else if (name == "v") {
    closed_u = false;
    closed_v = true;
  } else if (name == "uv" || name == "vu") {
    closed_u = closed_v = true;
  } else {
    return false;
  }
  return true;
}

std::string_view closed_to_string(bool closed_u, bool closed_v) {
  return closed_u ? (closed_v ? "uv" : "u") : (closed_v ? "v" : "none");
}

}  // namespace sfit
