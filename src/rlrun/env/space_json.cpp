#include "rlrun/env/space_json.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rlrun {

using nlohmann::json;

namespace {

json bound_to_json(float v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return static_cast<double>(v);
}

// One value or, when every element has the same, that value alone (an image's 0..255).
json bounds_to_json(const std::vector<float>& values) {
  bool uniform = true;
  for (float v : values) uniform = uniform && v == values.front();
  if (uniform && !values.empty()) return bound_to_json(values.front());
  json list = json::array();
  for (float v : values) list.push_back(bound_to_json(v));
  return list;
}

float bound_from_json(const json& v) {
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    if (s == "inf") return std::numeric_limits<float>::infinity();
    if (s == "-inf") return -std::numeric_limits<float>::infinity();
    throw std::invalid_argument("a Box bound is '" + s + "'");
  }
  if (!v.is_number()) throw std::invalid_argument("a Box bound is " + v.dump(-1).substr(0, 40));
  // float32 as numpy's Box.low.astype(np.float32): beyond float32's range is +-inf.
  return static_cast<float>(v.get<double>());
}

std::vector<float> bounds_from_json(const json& v, int64_t size, const char* which) {
  if (!v.is_array()) return std::vector<float>(static_cast<size_t>(size), bound_from_json(v));
  if (static_cast<int64_t>(v.size()) != size)
    throw std::invalid_argument(std::string("a Box's ") + which + " has " +
                                std::to_string(v.size()) + " values for " + std::to_string(size) +
                                " elements");
  std::vector<float> out;
  out.reserve(static_cast<size_t>(size));
  for (const json& b : v) out.push_back(bound_from_json(b));
  return out;
}

// A count of a Discrete or MultiDiscrete space. Python's ints have no bound: one beyond int64
// arrives as a float or an unsigned number, and is refused as written.
int64_t count_from_json(const json& v, const std::string& what) {
  if (v.is_number_integer() && !(v.is_number_unsigned() &&
                                 v.get<uint64_t>() > uint64_t{std::numeric_limits<int64_t>::max()}))
    return v.get<int64_t>();
  if (!v.is_number() || (v.is_number_float() && std::isfinite(v.get<double>()) &&
                         v.get<double>() != std::floor(v.get<double>())))
    throw std::invalid_argument(what + " is not a whole number: " + v.dump().substr(0, 40));
  throw std::invalid_argument(Space::too_many_values(what + " of " + v.dump()));
}

// A number of floats, checked against kMaxJsonSpaceFloats before any use.
int64_t floats_from_json(const json& v, const std::string& what) {
  const int64_t n = count_from_json(v, what);
  if (n < 0 || n > kMaxJsonSpaceFloats)
    throw std::invalid_argument(what + " is " + std::to_string(n) + "; rlrun takes 0 to " +
                                std::to_string(kMaxJsonSpaceFloats) + " floats per sample");
  return n;
}

const json& member(const json& j, const char* key, const std::string& kind) {
  const auto it = j.find(key);
  if (it == j.end()) throw std::invalid_argument("a " + kind + " space has no \"" + key + "\"");
  return *it;
}

// A Box's "dtype": "uint8" keeps its images as bytes; any other numpy dtype name (a Python env
// sends its space's, e.g. "float64") and none at all are float32, rlrun's one number type.
BoxDtype box_dtype_from_json(const json& j) {
  const auto dtype = j.find("dtype");
  if (dtype == j.end()) return BoxDtype::kFloat32;
  if (!dtype->is_string()) throw std::invalid_argument("a Box's dtype is not a string");
  return dtype->get<std::string>() == "uint8" ? BoxDtype::kUint8 : BoxDtype::kFloat32;
}

Space decode(const json& j, bool inside_dict) {
  if (!j.is_object()) throw std::invalid_argument("a space is a JSON object with a \"kind\"");
  const json& kind_json = member(j, "kind", "");
  if (!kind_json.is_string()) throw std::invalid_argument("a space's kind is not a string");
  const std::string kind = kind_json.get<std::string>();
  if (kind == "Box") {
    const json& shape_json = member(j, "shape", kind);
    if (!shape_json.is_array() || shape_json.empty() || shape_json.size() > 8)
      throw std::invalid_argument("a Box's shape is a list of 1 to 8 sizes");
    std::vector<int> shape;
    int64_t size = 1;
    for (const json& d : shape_json) {
      const int64_t n = floats_from_json(d, "a Box dimension");
      size *= n;  // each factor <= 2^24 and the running product checked below: no overflow
      if (size > kMaxJsonSpaceFloats)
        throw std::invalid_argument("a Box of more than " + std::to_string(kMaxJsonSpaceFloats) +
                                    " floats");
      shape.push_back(static_cast<int>(n));
    }
    return Space::box(bounds_from_json(member(j, "low", kind), size, "low"),
                      bounds_from_json(member(j, "high", kind), size, "high"), std::move(shape),
                      box_dtype_from_json(j));
  }
  if (kind == "Discrete") {
    const int64_t n = count_from_json(member(j, "n", kind), "a Discrete space");
    const auto start = j.find("start");
    return Space::discrete(n, start == j.end() ? 0 : count_from_json(*start, "a Discrete start"));
  }
  if (kind == "MultiDiscrete") {
    const json& nvec_json = member(j, "nvec", kind);
    if (!nvec_json.is_array() || static_cast<int64_t>(nvec_json.size()) > kMaxJsonSpaceFloats)
      throw std::invalid_argument("a MultiDiscrete's nvec is a list of at most " +
                                  std::to_string(kMaxJsonSpaceFloats) + " counts");
    std::vector<int64_t> nvec;
    for (const json& n : nvec_json) nvec.push_back(count_from_json(n, "a MultiDiscrete entry"));
    return Space::multi_discrete(std::move(nvec));
  }
  if (kind == "MultiBinary")
    return Space::multi_binary(
        static_cast<int>(floats_from_json(member(j, "n", kind), "a MultiBinary size")));
  if (kind == "Dict") {
    if (inside_dict)
      throw std::invalid_argument("a Dict inside a Dict; one level of keys is supported (as SB3)");
    const json& spaces = member(j, "spaces", kind);
    if (!spaces.is_object()) throw std::invalid_argument("a Dict's spaces are a JSON object");
    std::vector<std::pair<std::string, Space>> entries;
    int64_t floats = 0;
    for (const auto& [key, sub] : spaces.items()) {
      entries.emplace_back(key, decode(sub, true));
      floats += entries.back().second.flat_dim();
      if (floats > kMaxJsonSpaceFloats)
        throw std::invalid_argument("a Dict of more than " + std::to_string(kMaxJsonSpaceFloats) +
                                    " floats");
    }
    return Space::dict(std::move(entries));
  }
  throw std::invalid_argument("unknown space kind '" + kind + "'");
}

}  // namespace

json space_to_json(const Space& space) {
  json j;
  j["kind"] = space_kind_name(space.kind());
  switch (space.kind()) {
    case SpaceKind::kBox:
      j["shape"] = space.shape();
      j["low"] = bounds_to_json(space.low());
      j["high"] = bounds_to_json(space.high());
      // Only uint8 is written: float32 Boxes read the same by rlrun versions before dtypes.
      if (space.is_uint8_box()) j["dtype"] = box_dtype_name(space.dtype());
      break;
    case SpaceKind::kDiscrete:
      j["n"] = space.n();
      j["start"] = space.start();
      break;
    case SpaceKind::kMultiDiscrete: j["nvec"] = space.nvec(); break;
    case SpaceKind::kMultiBinary: j["n"] = space.n(); break;
    case SpaceKind::kDict: {
      json spaces = json::object();
      for (size_t i = 0; i < space.keys().size(); ++i)
        spaces[space.keys()[i]] = space_to_json(space.subspaces()[i]);
      j["spaces"] = spaces;
      break;
    }
  }
  return j;
}

Space space_from_json(const json& j) {
  try {
    return decode(j, false);
  } catch (const json::exception& e) {
    throw std::invalid_argument(std::string("a space's JSON is malformed: ") + e.what());
  }
}

}  // namespace rlrun
