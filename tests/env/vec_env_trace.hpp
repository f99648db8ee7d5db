#pragma once
// What a VecEnv gave over a run of random actions, to compare two ways of stepping the same
// envs (in halves, on a thread pool) with stepping one copy after another, bit for bit.
#include <cstdint>
#include <vector>

#include "rlrun/env/vec_env.hpp"
#include "rlrun/rng.hpp"

namespace rlrun::testing {

struct VecEnvTrace {
  std::vector<float> obs, final_obs;
  std::vector<double> rewards;
  std::vector<int> dones;
};

// Seeds the envs with `seed`, resets, then `steps` steps of actions drawn from Rng(7).
inline VecEnvTrace trace_random_steps(VecEnv& env, int steps, uint64_t seed) {
  VecEnvTrace t;
  env.seed(seed);
  env.reset();
  Rng rng(7);
  Eigen::MatrixXf actions(env.action_space().flat_dim(), env.num_envs());
  for (int s = 0; s < steps; ++s) {
    for (int c = 0; c < env.num_envs(); ++c)
      env.action_space().sample(rng, {actions.col(c).data(), static_cast<size_t>(actions.rows())});
    env.step(actions);
    for (int c = 0; c < env.num_envs(); ++c) {
      t.rewards.push_back(env.rewards()[c]);
      t.dones.push_back(env.done(c));
      for (int k = 0; k < env.obs().rows(); ++k) {
        t.obs.push_back(env.obs()(k, c));
        if (env.done(c)) t.final_obs.push_back(env.final_obs()(k, c));
      }
    }
  }
  return t;
}

}  // namespace rlrun::testing
