#pragma once
// A replay batch for the Q-network family's tests (DQN, QR-DQN): observations and next
// observations uniform in [-1, 1], actions uniform over n_actions, rewards in [-2, 2], every
// fourth transition terminal.
#include "rlrun/algos/common/replay_buffer.hpp"
#include "rlrun/rng.hpp"

namespace rlrun::test {

inline ReplayBatch random_discrete_batch(Rng& rng, int obs_dim, int n_actions, int n) {
  ReplayBatch b;
  b.obs.resize(obs_dim, n);
  b.next_obs.resize(obs_dim, n);
  b.actions.resize(1, n);
  b.rewards.resize(n);
  b.dones.resize(n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < obs_dim; ++i) {
      b.obs(i, j) = static_cast<float>(rng.uniform(-1, 1));
      b.next_obs(i, j) = static_cast<float>(rng.uniform(-1, 1));
    }
    b.actions(0, j) = static_cast<float>(rng.below(n_actions));
    b.rewards(j) = static_cast<float>(rng.uniform(-2, 2));
    b.dones(j) = j % 4 == 0 ? 1.0f : 0.0f;
  }
  return b;
}

}  // namespace rlrun::test
