#include "sfit/io/options_json.h"

#include <string>

namespace sfit::io {

nlohmann::json option_table_json() {
  nlohmann::json out = nlohmann::json::array();
  for (const OptionSpec& s : option_table()) {
    nlohmann::json o{{"name", s.name},
                     {"flag", s.flag},
                     {"group", to_string(s.group)},
                     {"type", to_string(s.type)},
                     {"help", s.help}};
    const std::string d(s.default_value);
    if (d.empty())
      o["default"] = nullptr;
    else if (s.type == OptionType::kInteger)
      o["default"] = std::stoll(d);
    else if (s.type == OptionType::kNumber)
      o["default"] = std::stod(d);
    else if (s.type == OptionType::kFlag)
      o["default"] = d == "true";
    else
      o["default"] = d;
    if (s.type == OptionType::kInteger) {
      o["min"] = static_cast<long long>(s.min);
      o["max"] = static_cast<long long>(s.max);
    } else if (s.type == OptionType::kNumber) {
      o["min"] = s.min;
      o["max"] = s.max;
    }
    if (s.type == OptionType::kChoice) {
      o["choices"] = nlohmann::json::array();
      for (std::string_view c : s.choices) o["choices"].push_back(c);
    }
    out.push_back(std::move(o));
  }
  return out;
}

}  // namespace sfit::io
