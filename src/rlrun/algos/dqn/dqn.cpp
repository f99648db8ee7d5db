#include "rlrun/algos/dqn/dqn.hpp"

#include <algorithm>
#include <cmath>

#include "rlrun/core/config_validation.hpp"

namespace rlrun {

namespace {
// Replay sampling: DQN's own stream, drawn before algos/common/rng_streams.hpp named them (it is
// kNoiseStream's word; fixed forever, as every stream is). Exploration is kActionStream.
constexpr uint64_t kReplayStream = 0x2545f4914f6cdd1dULL;

// Validates before the networks are built from the config: the fields' constraints (visit),
// then what the Q-network family adds (Discrete actions, tau > 0).
const DQN::Config& checked(const DQN::Config& c, const AlgorithmSetup& setup) {
  valid_config(c, "DQN");
  require_q_learning_setup("DQN", c.off_policy, setup);
  return c;
}
}  // namespace

ConfigProblems DQN::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  check_q_learning(out, config.off_policy, config.policy, 1, setup);
  return out;
}

DQN::DQN(const Config& config, const AlgorithmSetup& setup)
    : QLearningAlgorithm("DQN", checked(config, setup).off_policy, setup,
                         // SB3 2.x DQNPolicy: Adam over q_net with torch's defaults.
                         q_learning_settings(config, config.policy, 1, AdamConfig{}, "q_net"),
                         {kReplayStream, "replay_rng"}),
      config_(config) {}

// SB3 dqn/dqn.py DQN.train, one pass of its loop over gradient steps (CleanRL's dqn.py has the
// same steps with an MSE loss and no gradient clipping).
double DQN::train_on_batch(const ReplayBatch& b, float lr) {
  const Eigen::Index n = b.obs.cols();
  const float inv_n = 1.0f / static_cast<float>(n);
  const auto gamma = static_cast<float>(config_.off_policy.gamma);

  // with th.no_grad():
  //   next_q_values = q_net_target(next_obs).max(dim=1)
  //   target_q_values = rewards + (1 - dones) * gamma * next_q_values
  const Eigen::MatrixXf& next_q = target_outputs(b);
  targets_.resize(n);
  for (Eigen::Index j = 0; j < n; ++j)
    targets_(j) = b.rewards(j) + (1.0f - b.dones(j)) * gamma * next_q.col(j).maxCoeff();

  // current_q_values = th.gather(q_net(obs), dim=1, index=actions)
  // loss = F.smooth_l1_loss(current_q_values, target_q_values): 0.5 d^2 where |d| < 1, else
  // |d| - 0.5, averaged; its gradient is d clamped to [-1, 1], over n, at the taken actions.
  const Eigen::MatrixXf& q = online_outputs(b);
  grad_q_.setZero(q.rows(), n);
  double loss = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index a = buffer_action(b, j);
    const float diff = q(a, j) - targets_(j);
    const float abs_diff = std::abs(diff);
    loss += abs_diff < 1.0f ? 0.5 * static_cast<double>(diff) * diff : abs_diff - 0.5;
    grad_q_(a, j) = std::clamp(diff, -1.0f, 1.0f) * inv_n;
  }

  // optimizer.zero_grad(); loss.backward();
  // th.nn.utils.clip_grad_norm_(q_net.parameters(), max_grad_norm); optimizer.step()
  backward_and_step(grad_q_, lr, config_.max_grad_norm);
  return loss / static_cast<double>(n);
}

}  // namespace rlrun
