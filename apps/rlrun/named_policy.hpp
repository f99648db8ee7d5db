#pragma once
// The policies that need no model file, by name, for `eval --policy` and `record --policy`:
//   random      uniform actions from the action space, their own stream seeded from `seed`
//   fixed-time  the traffic task's N -> S -> E -> W plan (`green_time` s per approach)
//   scripted    the grasp task's controller
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>

#include "rlrun/env.hpp"

namespace rlrun::cli {

struct NamedPolicy {
  std::function<void(const Eigen::MatrixXf& obs, Eigen::MatrixXf& action)> act;
  std::string label;  // for overlays and summaries, e.g. "fixed-time 30 s"
};

// Throws UsageError for another name, or when the policy does not fit `env`.
NamedPolicy named_policy(const std::string& name, Env& env, uint64_t seed, int green_time);

}  // namespace rlrun::cli
