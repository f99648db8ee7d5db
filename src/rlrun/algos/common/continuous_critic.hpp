#pragma once
// SB3 common/policies.py ContinuousCritic, the critic of SAC, TD3 and DDPG: n_critics
// Q-networks q_networks[i] = create_mlp(obs_dim + action_dim, 1, net_arch) on concat(obs,
// action), saved as <prefix>.qf<i>.*. The algorithms hold two: `critic` and `critic_target`, a
// copy (load_state_dict) that then only moves by Polyak averaging. Each Q-network is a SplitMlp,
// so a training minibatch runs on both cores; the losses are the algorithms'.
//
// With n_outputs > 1 it is sb3-contrib tqc/policies.py Critic: each network ends in
// n_quantiles outputs (create_mlp(features_dim + action_dim, n_quantiles, net_arch)), with the
// same module names qf<i>, so the same class, save names and Polyak update serve TQC.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/batch_split.hpp"
#include "rlrun/nn/split_mlp.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

class ContinuousCritic {
 public:
  // Parameters start at zero: call init (or copy another critic). Throws std::invalid_argument
  // for n_critics < 1, n_outputs < 1 or bad sizes. n_outputs: 1 (a Q-value) or TQC's
  // n_quantiles. `pool` runs a minibatch's parts (SplitMlp) or the critics side by side.
  ContinuousCritic(int obs_dim, int action_dim, const std::vector<int>& net_arch,
                   Activation activation, int n_critics, int n_outputs = 1,
                   ThreadPool* pool = nullptr);

  // torch's default Linear init, Q-network by Q-network (SB3 never calls init_weights for
  // off-policy critics).
  void init(Rng& rng);

  int n_critics() const { return static_cast<int>(q_.size()); }
  int n_outputs() const { return q_.front().net().out_dim(); }
  SplitMlp& q(int i) { return q_[i]; }
  const SplitMlp& q(int i) const { return q_[i]; }

  // Runs fn(i) for every critic i, critics 0, 2, ... as one part and 1, 3, ... as another on
  // the pool (core/thread_pool.hpp) when a pass of n columns through one critic does not
  // already split (nn/batch_split.hpp): small critics such as RLtools' 64x64 ones still use a
  // second core. fn(i) must read and write only critic i's state (its network, optimizer
  // and buffers). Which critics run together depends on sizes only, so results do not depend
  // on the thread count.
  template <class F>
  void for_each_critic(Eigen::Index n, F&& fn) {
    const int critics = n_critics();
    const bool apart =
        critics > 1 && column_parts(n, q_.front().net().multiply_adds_per_column()) == 1;
    run_parts(pool_, apart ? 2 : 1, [&](int part) {
      for (int i = apart ? part : 0; i < critics; i += apart ? 2 : 1) fn(i);
    });
  }

  // SB3 forward(obs, actions): Q_i(obs, actions) of every critic, each q(i).output()
  // (n_outputs x n), kept for backward (the actions: action_dim x n).
  void forward(const Eigen::Ref<const Eigen::MatrixXf>& obs,
               const Eigen::Ref<const Eigen::MatrixXf>& actions);
  // th.min over the critics of sample j's values in the last forward: the first critic with
  // the smallest (where th.min sends the gradient), and that value. n_outputs == 1 only.
  int argmin(Eigen::Index j) const;
  float min(Eigen::Index j) const { return q_[argmin(j)].output()(0, j); }
  // SB3 q1_forward: the first critic only (TD3's actor loss).
  const Eigen::MatrixXf& q1_forward(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                    const Eigen::Ref<const Eigen::MatrixXf>& actions);
  // dL/d(actions) through critic i's last forward for dL/dQ_i = grad_q (n_outputs x n):
  // action_dim x n.
  // Input gradient only: an actor loss's backward also fills the critic's .grad in torch, but
  // the critic optimizer's zero_grad() clears it before its next step, so it is never used.
  void action_gradient(int i, const Eigen::Ref<const Eigen::MatrixXf>& grad_q,
                       Eigen::MatrixXf& grad_actions);

  // SB3 state_dict names: <prefix>.qf<i>.<2l>.weight/bias, e.g. critic.qf0.0.weight and
  // critic.qf0.4.weight for net_arch [256, 256] (torch Sequential indices skip activations).
  void save(const std::string& prefix, TensorMap& tensors) const;
  void load(const std::string& prefix, const TensorMap& tensors);

 private:
  int obs_dim_ = 0;
  ThreadPool* pool_ = nullptr;
  std::vector<SplitMlp> q_;
  Eigen::MatrixXf obs_action_;
};

// SB3 polyak_update(critic.parameters(), critic_target.parameters(), tau).
void polyak_update(const ContinuousCritic& critic, ContinuousCritic& target, float tau);

}  // namespace rlrun
