#include "rlrun/env/space_text.hpp"
#include "rlrun/core/plural.hpp"

#include <algorithm>
#include <sstream>

namespace rlrun {

namespace {

std::string format_number(float v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string format_flat(std::span<const float> x) {
  std::string out = "[";
  for (size_t i = 0; i < x.size(); ++i) out += (i ? ", " : "") + format_number(x[i]);
  return out + "]";
}

std::span<const float> key_values(const Space& dict, size_t i, std::span<const float> x) {
  return x.subspan(static_cast<size_t>(dict.offset(i)),
                   static_cast<size_t>(dict.subspaces()[i].flat_dim()));
}

std::string floats_range(int begin, int size) {
  // Appends (GCC 12 warns, wrongly, with -Wrestrict about "[" + std::to_string(...)).
  std::string text = "[";
  text.append(std::to_string(begin)).append(", ").append(std::to_string(begin + size)).append(")");
  return text;
}

// The first entry of a non-Dict value outside its space, "" if none.
std::string entry_outside(const Space& space, std::span<const float> x) {
  if (space.contains(x)) return "";
  if (static_cast<int>(x.size()) != space.flat_dim())
    return "has " + count_of(static_cast<int64_t>(x.size()), "value") + ", not " +
           std::to_string(space.flat_dim());
  if (x.size() == 1) return "is " + format_number(x[0]) + ", not in " + space.describe();
  for (size_t i = 0; i < x.size(); ++i) {
    bool inside = true;
    switch (space.kind()) {
      case SpaceKind::kBox: inside = x[i] >= space.low()[i] && x[i] <= space.high()[i]; break;
      case SpaceKind::kMultiDiscrete:
        inside = x[i] == static_cast<float>(static_cast<int64_t>(x[i])) && x[i] >= 0 &&
                 x[i] < static_cast<float>(space.nvec()[i]);
        break;
      case SpaceKind::kMultiBinary: inside = x[i] == 0.0f || x[i] == 1.0f; break;
      default: break;
    }
    if (!inside)
      return "entry " + std::to_string(i) + " is " + format_number(x[i]) + ", not in " +
             space.describe();
  }
  return "is not in " + space.describe();
}

}  // namespace

std::string format_value(const Space& space, std::span<const float> x) {
  if (!space.is_dict() || static_cast<int>(x.size()) != space.flat_dim()) return format_flat(x);
  std::string out = "{";
  for (size_t i = 0; i < space.keys().size(); ++i)
    out += (i ? ", '" : "'") + space.keys()[i] + "': " + format_flat(key_values(space, i, x));
  return out + "}";
}

std::string outside_reason(const Space& space, std::span<const float> x) {
  if (!space.is_dict() || static_cast<int>(x.size()) != space.flat_dim())
    return entry_outside(space, x);
  for (size_t i = 0; i < space.keys().size(); ++i) {
    const std::string why = entry_outside(space.subspaces()[i], key_values(space, i, x));
    if (!why.empty()) return "key '" + space.keys()[i] + "' " + why;
  }
  return "";
}

std::vector<std::string> describe_lines(const Space& space) {
  if (!space.is_dict()) return {space.describe()};
  std::vector<std::string> lines{"Dict (" + std::to_string(space.flat_dim()) +
                                 " floats, keys in sorted order)"};
  for (size_t i = 0; i < space.keys().size(); ++i) {
    const Space& key = space.subspaces()[i];
    lines.push_back("'" + space.keys()[i] + "': " + key.describe() + "  floats " +
                    floats_range(space.offset(i), key.flat_dim()));
  }
  return lines;
}

std::string labeled_space(const std::string& label, const Space& space, int label_width) {
  const size_t width = static_cast<size_t>(std::max(label_width, static_cast<int>(label.size())));
  std::string text;
  const std::vector<std::string> lines = describe_lines(space);
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string head = i == 0 ? label : "";
    text += "  " + head + std::string(width - head.size(), ' ') + (i == 0 ? "  " : "    ") +
            lines[i] + "\n";
  }
  return text;
}

std::string flat_layout(const Space& space) {
  std::string text = std::to_string(space.flat_dim()) + " floats";
  for (size_t i = 0; i < space.keys().size(); ++i)
    text += (i ? ", '" : ": '") + space.keys()[i] + "' " +
            floats_range(space.offset(i), space.subspaces()[i].flat_dim());
  return text;
}

}  // namespace rlrun
