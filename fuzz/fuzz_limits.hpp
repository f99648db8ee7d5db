#pragma once
// What the fuzz targets leave out of an experiment config, and why:
//  * a `plugins:` section: it dlopen()s the libraries it names — loading code, not parsing, and
//    a fuzzer must not load arbitrary system libraries into itself;
//  * numbers between kFuzzMaxNumber and kFuzzHugeNumber in the env and algo sections: they size
//    networks, buffers and env copies. A config may legitimately ask for a 10^6-transition
//    buffer or 4096-wide layers; building those is slow, not wrong, and would only make the
//    fuzzer report its own memory and time limits. Larger numbers (beyond any integer setting:
//    range checks, float overflow) and all others are fuzzed.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "rlrun/core/config_node.hpp"

namespace rlrun::fuzz {

inline constexpr double kFuzzMaxNumber = 1024;
inline constexpr double kFuzzHugeNumber = 1e16;

// `budget` counts the nodes visited: aliases can make a small document a huge tree, which this
// walk must not expand (such configs are fuzzed by the parse, just not size-checked here).
inline bool small_numbers(const YAML::Node& node, int& budget, int depth = 0) {
  if (!node.IsDefined() || node.IsNull()) return true;
  if (depth > 64 || --budget < 0) return false;
  if (node.IsScalar()) {
    const std::string& text = node.Scalar();
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    return end == text.c_str() || !(std::fabs(value) > kFuzzMaxNumber) ||
           !(std::fabs(value) < kFuzzHugeNumber);
  }
  for (const auto& item : node) {
    if (node.IsMap() ? !small_numbers(item.first, budget, depth + 1) ||
                           !small_numbers(item.second, budget, depth + 1)
                     : !small_numbers(item, budget, depth + 1))
      return false;
  }
  return true;
}

// True when the fuzz targets run this config (see above).
inline bool fuzzable_config(const ConfigNode& root) {
  if (!root.is_map()) return true;
  if (root.child("plugins").defined()) return false;
  int budget = 10000;
  return small_numbers(root.child("env").yaml(), budget) &&
         small_numbers(root.child("algo").yaml(), budget);
}

}  // namespace rlrun::fuzz
