// libFuzzer target: the surface JSON reader (surface_from_json) on arbitrary bytes. A
// surface it accepts must be finite, evaluate to finite points, and survive a round trip
// through surface_to_json unchanged; anything else must be Error(kInputSyntax/kInputData).
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "fuzz_common.h"
#include "surface_json_value.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sfit;
  const nlohmann::json j = nlohmann::json::parse(data, data + size, nullptr, false);
  if (j.is_discarded()) return 0;
  Surface s;
  try {
    s = io::surface_from_json(j, "fuzz.json");
  } catch (const Error& e) {
    fuzz::check_error(e, ErrorCode::kInputSyntax, ErrorCode::kInputData);
    return 0;
  }
  if (s.count_u < 1 || s.count_v < 1 ||
      s.control.size() != static_cast<std::size_t>(s.count_u) * s.count_v)
    fuzz::finding("accepted a surface with inconsistent counts");
  for (const Point& p : s.control)
    if (!p.allFinite()) fuzz::finding("accepted a non-finite control point");
  for (int a = 0; a <= 4; ++a)
    for (int b = 0; b <= 4; ++b)
      if (!s.evaluate(0.25 * a * s.u_end(), 0.25 * b * s.v_end()).allFinite())
        fuzz::finding("a finite surface evaluated to a non-finite point");
  const Surface back = io::surface_from_json(io::surface_to_json(s), "round trip");
  if (back.degree_u != s.degree_u || back.degree_v != s.degree_v ||
      back.periodic_u != s.periodic_u || back.periodic_v != s.periodic_v ||
      back.count_u != s.count_u || back.count_v != s.count_v || back.control != s.control)
    fuzz::finding("surface_to_json / surface_from_json round trip changed the surface");
  return 0;
}
