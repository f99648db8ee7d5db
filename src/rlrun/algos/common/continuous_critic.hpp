#pragma once
// One Q-network of SAC, TD3 or DDPG with its target copy. SB3 common/policies.py
// ContinuousCritic builds q_networks[i] = create_mlp(obs_dim + action_dim, 1, net_arch) on
// concat(obs, action); sac/policies.py and td3/policies.py add a critic_target that starts as a
// copy (load_state_dict) and then only moves by Polyak averaging.
//
// SB3 steps all critics with ONE Adam over their concatenated parameters. Adam is element-wise
// with one step count, so one Adam per critic is the same update; the optimizers live with the
// algorithm, because a batch may be split over replicas of this network (batch_lanes.hpp).
// Every method reads its inputs and writes only this critic's members, so critics, and
// replicas working on different columns of a batch, can run on different cores.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/rng.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/mlp.hpp"

namespace rlrun {

class ContinuousCritic {
 public:
  // input_dim = obs_dim + action_dim. Parameters start at zero: call init (or copy them in).
  ContinuousCritic(int input_dim, const std::vector<int>& net_arch, Activation activation);

  // torch's default Linear init from rng (SB3 never calls init_weights for off-policy critics);
  // the target becomes a copy.
  void init(Rng& rng);

  Mlp& q() { return q_; }
  const Mlp& q() const { return q_; }
  Mlp& target() { return target_; }
  const Mlp& target() const { return target_; }

  // Q_target(obs_action) -> target_values(), 1 x n (th.no_grad: nothing is kept for a backward
  // pass through the target).
  void compute_target_values(const Eigen::Ref<const Eigen::MatrixXf>& obs_action);
  const Eigen::MatrixXf& target_values() const { return target_values_; }

  // This critic's term of a squared-error critic loss over the samples given: zeroes the
  // gradient, runs Q(obs_action), returns scale * sum_j (Q_j - y_j)^2 and leaves its gradient
  // in q().grads(). y is 1 x n. TD3's F.mse_loss over a batch of B is scale = 1 / B, SAC's
  // 0.5 * F.mse_loss is scale = 0.5 / B; with B the WHOLE batch, the parts of a batch split over
  // replicas add up to the loss and gradient of the whole.
  double loss_and_gradient(const Eigen::Ref<const Eigen::MatrixXf>& obs_action,
                           const Eigen::Ref<const Eigen::MatrixXf>& y, float scale);

  // The actor loss runs through the critic: Q(obs_action) with the current parameters ->
  // values() (1 x n), kept for compute_action_gradient().
  void compute_values(const Eigen::Ref<const Eigen::MatrixXf>& obs_action);
  const Eigen::MatrixXf& values() const { return values_; }
  // dL/d(action) for dL/dQ = grad_q (1 x n) at the last compute_values() input: the bottom
  // action_dim rows of dL/d(obs_action) -> action_gradient() (action_dim x n). Input gradient
  // only: torch's actor_loss.backward() also fills the critic's .grad, but the critic's
  // optimizer.zero_grad() clears it before its next step, so it is never used, and skipping it
  // halves this backward pass. q().grads() is left unchanged.
  void compute_action_gradient(const Eigen::Ref<const Eigen::MatrixXf>& grad_q, int action_dim);
  const Eigen::MatrixXf& action_gradient() const { return action_gradient_; }

  // SB3 polyak_update(critic.parameters(), critic_target.parameters(), tau).
  void soft_update(float tau);

  // Copies the online (and target) parameters of `primary`, for a replica lane.
  void pull_online(const ContinuousCritic& primary) { q_.params() = primary.q_.params(); }
  void pull_target(const ContinuousCritic& primary) {
    target_.params() = primary.target_.params();
  }

  // SB3 state_dict names: <prefix>.<2l>.weight/bias for layer l, e.g. critic.qf0.0.weight and
  // critic.qf0.4.weight for net_arch [256, 256] (torch Sequential indices skip activations).
  void save(const std::string& online_prefix, const std::string& target_prefix,
            TensorMap& tensors) const;
  void load(const std::string& online_prefix, const std::string& target_prefix,
            const TensorMap& tensors);

 private:
  Mlp q_, target_;
  Eigen::MatrixXf target_values_, values_, grad_values_, action_gradient_;
};

}  // namespace rlrun
