#pragma once
// One of SAC's (and TD3's) twin Q-networks: SB3 common/policies.py ContinuousCritic builds
// q_networks[i] = Linear -> act -> ... -> Linear(1) on concat(obs, action), and the policy keeps
// a critic_target copy (sac/policies.py SACPolicy._build) that only moves by Polyak averaging.
//
// SB3 steps all critics with ONE Adam over their concatenated parameters. Adam is element-wise
// with a shared step count, so one Adam per network gives bit-for-bit the same update; keeping
// each network, its target, its optimizer and its workspaces together means the per-critic
// phases of a SAC step touch disjoint state and can run on separate cores.
//
// Every method reads the shared inputs only and writes only this critic's members.
// Non-copyable: the optimizer points into the network's parameter storage (a move keeps the
// Eigen buffers, and so the pointers, valid).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/core/rng.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/adam.hpp"
#include "rlrun/nn/mlp.hpp"

namespace rlrun {

class SacCritic {
 public:
  // input_dim = obs_dim + action_dim. Torch default init of the online network from rng, the
  // target a copy (SB3: critic_target.load_state_dict(critic.state_dict())).
  SacCritic(int input_dim, const std::vector<int>& net_arch, Activation activation, Rng& rng,
            AdamConfig adam = {});
  SacCritic(const SacCritic&) = delete;
  SacCritic& operator=(const SacCritic&) = delete;
  SacCritic(SacCritic&&) = default;
  SacCritic& operator=(SacCritic&&) = default;

  Mlp& q() { return q_; }
  const Mlp& q() const { return q_; }
  Mlp& target() { return target_; }
  const Mlp& target() const { return target_; }
  Adam& optimizer() { return adam_; }
  const Adam& optimizer() const { return adam_; }

  // Q_target(obs_action) -> target_values(), 1 x batch (no gradient: th.no_grad()).
  void compute_target_values(const Eigen::Ref<const Eigen::MatrixXf>& obs_action);
  const Eigen::MatrixXf& target_values() const { return target_values_; }

  // This critic's term of SB3's critic_loss = 0.5 * sum_i mse(Q_i(obs, a), y): zeroes the
  // gradient, runs Q(obs_action), returns 0.5 * mean((Q - y)^2) and leaves its gradient in
  // q().grads(). `y` is 1 x batch.
  double loss_and_gradient(const Eigen::Ref<const Eigen::MatrixXf>& obs_action,
                           const Eigen::Ref<const Eigen::MatrixXf>& y);
  // Adam step on the gradient left by loss_and_gradient.
  void step(float lr) { adam_.step(lr); }

  // Q(obs_action) with the current parameters -> values() (1 x batch), kept for
  // action_gradient (SAC's actor loss runs through the just-updated critics).
  void compute_values(const Eigen::Ref<const Eigen::MatrixXf>& obs_action);
  const Eigen::MatrixXf& values() const { return values_; }

  // dL/d(action) for dL/dQ = grad_q (1 x batch) at the last compute_values() input: the
  // bottom action_dim rows of dL/d(obs_action) -> action_gradient(). As in torch's
  // actor_loss.backward(), this also adds to q().grads(), which loss_and_gradient() clears
  // before the critic's next update.
  void compute_action_gradient(const Eigen::Ref<const Eigen::MatrixXf>& grad_q, int action_dim);
  const Eigen::MatrixXf& action_gradient() const { return action_gradient_; }

  // SB3 polyak_update(critic.parameters(), critic_target.parameters(), tau).
  void soft_update(float tau);

  // SB3 names: <prefix>.<2i>.weight/bias for every layer, e.g. critic.qf0.0.weight,
  // critic.qf0.4.weight (torch Sequential indices skip the activations).
  void save(const std::string& online_prefix, const std::string& target_prefix,
            TensorMap& tensors) const;
  void load(const std::string& online_prefix, const std::string& target_prefix,
            const TensorMap& tensors);

 private:
  Mlp q_, target_;
  Adam adam_;
  Eigen::MatrixXf target_values_, values_, grad_values_, grad_input_, action_gradient_;
};

}  // namespace rlrun
