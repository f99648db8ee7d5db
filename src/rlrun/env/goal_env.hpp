#pragma once
// Goal-conditioned envs (Gymnasium-Robotics' GoalEnv contract, gymnasium_robotics/core.py):
// a Dict observation with keys `observation`, `achieved_goal` and `desired_goal`, and a reward
// that is a function of the achieved and desired goals alone, computed for many at once, so
// that a Hindsight Experience Replay buffer (algos/common/her_replay_buffer.hpp) can relabel
// stored transitions with other goals.
//
// A side interface (found by dynamic_cast on the innermost env), like env/split_step.hpp:
// the plugin binary interface (include/rlrun/env.hpp) is unchanged.
#include <Eigen/Core>

#include "rlrun/env.hpp"

namespace rlrun {

class GoalEnv {
 public:
  virtual ~GoalEnv() = default;
  // GoalEnv.compute_reward(achieved_goal, desired_goal, info) for a batch: goals are
  // goal_dim x n (one column each); `rewards` gets n values. Must not depend on the env's
  // state: it is called on transitions of other episodes.
  virtual void compute_reward(const Eigen::Ref<const Eigen::MatrixXf>& achieved,
                              const Eigen::Ref<const Eigen::MatrixXf>& desired,
                              Eigen::Ref<Eigen::RowVectorXf> rewards) const = 0;
};

// The env's GoalEnv (its innermost env's), or nullptr.
inline const GoalEnv* goal_env_of(Env& env) {
  return dynamic_cast<const GoalEnv*>(&env.unwrapped());
}

}  // namespace rlrun
