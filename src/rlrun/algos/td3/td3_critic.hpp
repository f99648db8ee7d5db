#pragma once
// One Q-network of TD3/DDPG with its target copy. SB3 common/policies.py ContinuousCritic
// builds q_networks[i] = create_mlp(obs_dim + action_dim, 1, net_arch) on concat(obs, action);
// td3/policies.py TD3Policy._build adds a critic_target that starts as a copy (load_state_dict)
// and then only moves by Polyak averaging. The optimizer lives with the algorithm (TD3 keeps one
// Adam per critic), because a batch may be split over several replicas of this network.
//
// Every method reads its inputs and writes only this critic's members, so the critics (and
// replicas working on different slices of a batch) can run on different cores.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/core/rng.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/mlp.hpp"

namespace rlrun {

class Td3Critic {
 public:
  // input_dim = obs_dim + action_dim. Parameters start at zero: call init (or copy them in).
  Td3Critic(int input_dim, const std::vector<int>& net_arch, Activation activation);

  // torch's default Linear init from rng (SB3 never calls init_weights for off-policy critics);
  // the target becomes a copy.
  void init(Rng& rng);

  Mlp& q() { return q_; }
  const Mlp& q() const { return q_; }
  Mlp& target() { return target_; }
  const Mlp& target() const { return target_; }

  // Q_target(obs_action) -> target_values(), 1 x batch (th.no_grad: nothing is kept for a
  // backward pass through the target).
  void compute_target_values(const Eigen::Ref<const Eigen::MatrixXf>& obs_action);
  const Eigen::MatrixXf& target_values() const { return target_values_; }

  // This critic's term of TD3's critic_loss = sum_i F.mse_loss(Q_i(obs, a), y) over the samples
  // given: zeroes the gradient, returns sum_j (Q_j - y_j)^2 * inv_batch and leaves its gradient
  // in q().grads(). y is 1 x n; inv_batch is 1 / (size of the whole batch), so the parts of a
  // batch split over replicas add up to the mean.
  double loss_and_gradient(const Eigen::Ref<const Eigen::MatrixXf>& obs_action,
                           const Eigen::Ref<const Eigen::MatrixXf>& y, float inv_batch);

  // The actor loss -mean(Q(obs, mu(obs))) of TD3.train runs through q1_forward: Q(obs_action)
  // -> values(), kept for action_gradient().
  void compute_values(const Eigen::Ref<const Eigen::MatrixXf>& obs_action);
  const Eigen::MatrixXf& values() const { return values_; }
  // dL/d(action) for dL/dQ = grad_q (1 x batch) at the last compute_values() input: the bottom
  // action_dim rows of dL/d(obs_action) -> action_gradient(). As torch's actor_loss.backward(),
  // this also adds to q().grads(); loss_and_gradient() clears them before the critic's next
  // update, so they never reach the critic's optimizer.
  void compute_action_gradient(const Eigen::Ref<const Eigen::MatrixXf>& grad_q, int action_dim);
  const Eigen::MatrixXf& action_gradient() const { return action_gradient_; }

  // SB3 polyak_update(critic.parameters(), critic_target.parameters(), tau).
  void soft_update(float tau);

  // SB3 state_dict names: <prefix>.<2l>.weight/bias for layer l, e.g. critic.qf0.0.weight and
  // critic.qf0.4.weight for net_arch [400, 300] (torch Sequential indices skip activations).
  void save(const std::string& online_prefix, const std::string& target_prefix,
            TensorMap& tensors) const;
  void load(const std::string& online_prefix, const std::string& target_prefix,
            const TensorMap& tensors);

 private:
  Mlp q_, target_;
  Eigen::MatrixXf target_values_, values_, grad_values_, grad_input_, action_gradient_;
};

}  // namespace rlrun
