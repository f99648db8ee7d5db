#pragma once
// Whether two YAML trees are the same: maps with the same keys in the same order, sequences,
// scalars of the same text, nulls (an emitted scalar must not turn into null or back, nor a map
// into a string). Used where written YAML is read back (zoo import's test and fuzz_zoo).
#include <yaml-cpp/yaml.h>

#include <cstddef>

namespace rlrun::testing {

inline bool same_yaml_tree(const YAML::Node& a, const YAML::Node& b) {
  if (a.Type() != b.Type()) return false;
  if (a.IsScalar()) return a.Scalar() == b.Scalar();
  if (a.IsNull()) return true;
  if (a.size() != b.size()) return false;
  if (a.IsSequence()) {
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!same_yaml_tree(a[i], b[i])) return false;
    return true;
  }
  for (auto ia = a.begin(), ib = b.begin(); ia != a.end(); ++ia, ++ib)
    if (ia->first.Scalar() != ib->first.Scalar() || !same_yaml_tree(ia->second, ib->second))
      return false;
  return true;
}

}  // namespace rlrun::testing
