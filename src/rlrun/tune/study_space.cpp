#include "rlrun/tune/study_space.hpp"

#include <cstdio>

#include "rlrun/core/config_node.hpp"

namespace rlrun::tune {

std::string yaml_text_of(const nlohmann::json& value) {
  if (value.is_string()) return yaml_double_quoted(value.get<std::string>());
  if (value.is_null()) return "null";
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number_float()) {
    const double x = value.get<double>();
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", x);
    return text;
  }
  return value.dump();
}

}  // namespace rlrun::tune
