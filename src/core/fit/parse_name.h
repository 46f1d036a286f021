// The value among `values` whose to_string() is `name`: the one reading of the library's
// enumerated option names (sfit/option_names.h, sfit/parametrization.h, sfit/surface_fit.h).
#pragma once

#include <initializer_list>
#include <string_view>

namespace sfit::detail {

template <class E>
bool parse_name(std::string_view name, std::initializer_list<E> values, E& out) {
  for (E v : values)
    if (name == to_string(v)) {
      out = v;
      return true;
    }
  return false;
}

}  // namespace sfit::detail
