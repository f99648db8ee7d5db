#pragma once
// tests/data/sb3/: model files the real SB3 2.4.1 (and sb3-contrib 2.4.0) saved, with their
// reference observations and actions (scripts/data/make_sb3_models.sh).
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "rlrun/core/npy.hpp"
#include "test_paths.hpp"

namespace rlrun::testing {

inline std::string sb3_case_dir(const std::string& name) {
  return std::string(RLRUN_SOURCE_DIR) + "/tests/data/sb3/" + name;
}

inline Tensor read_npy_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  return decode_npy(bytes, path);
}

}  // namespace rlrun::testing
