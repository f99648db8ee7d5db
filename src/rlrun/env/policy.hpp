#pragma once
// A policy as evaluation and recording run it: observations (obs_dim x batch) in, env-ready
// actions (act_dim x batch) out. Trained models, a uniform random policy and an env's own
// baselines (the traffic task's fixed-time plan, the grasp task's scripted controller) all
// take this shape.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <map>
#include <string>

namespace rlrun {

using PolicyFn = std::function<void(const Eigen::MatrixXf& obs, Eigen::MatrixXf& action)>;

// What a named baseline may be told from the command line.
struct PolicyOptions {
  uint64_t seed = 0;
  std::map<std::string, double> settings;  // e.g. {"green_time", 30} (--green-time)
};

}  // namespace rlrun
