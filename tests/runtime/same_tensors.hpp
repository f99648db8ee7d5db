#pragma once
// Two model files hold the same tensors, byte for byte (their config.yaml may name other run
// directories): the check of every "the result does not depend on X" test.
#include <catch2/catch.hpp>
#include <string>

#include "rlrun/runtime/io/model_file.hpp"

namespace rlrun::testing {

inline void check_same_tensors(const std::string& path_a, const std::string& path_b) {
  const ModelFile a = read_model(path_a);
  const ModelFile b = read_model(path_b);
  REQUIRE(a.tensors.size() == b.tensors.size());
  for (const auto& [name, tensor] : a.tensors) {
    INFO(name);
    REQUIRE(b.tensors.count(name) == 1);
    CHECK(tensor.bytes == b.tensors.at(name).bytes);
  }
}

}  // namespace rlrun::testing
