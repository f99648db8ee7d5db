#pragma once
// SB3 common/policies.py ContinuousCritic, the critic of SAC, TD3 and DDPG: n_critics
// Q-networks q_networks[i] = create_mlp(obs_dim + action_dim, 1, net_arch) on concat(obs,
// action), saved as <prefix>.qf<i>.*. The algorithms hold two: `critic` and `critic_target`, a
// copy (load_state_dict) that then only moves by Polyak averaging. Each Q-network is a SplitMlp,
// so a training minibatch runs on both cores; the losses are the algorithms'.
//
// The Q-networks read the output of the critic's features extractor (features_extractor_net.hpp):
// the observation itself (FlattenExtractor) or a NatureCNN's features. SB3's off-policy
// CnnPolicy gives the critic its own CNN (share_features_extractor=False), read by every
// Q-network and trained by their summed loss, and a copy in critic_target averaged with the
// rest of it; so does this class (the extractor is saved as <prefix>.features_extractor.*).
//
// With n_outputs > 1 it is sb3-contrib tqc/policies.py Critic: each network ends in
// n_quantiles outputs (create_mlp(features_dim + action_dim, n_quantiles, net_arch)), with the
// same module names qf<i>, so the same class, save names and Polyak update serve TQC.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/algos/common/features_extractor_net.hpp"
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
  // The same behind a features extractor: the Q-networks read extractor.out_dim() features.
  ContinuousCritic(FeaturesExtractorNet extractor, int action_dim, const std::vector<int>& net_arch,
                   Activation activation, int n_critics, int n_outputs = 1,
                   ThreadPool* pool = nullptr);

  // torch's default Linear init, Q-network by Q-network (SB3 never calls init_weights for
  // off-policy critics). A learned extractor is initialised apart (features_extractor()).
  void init(Rng& rng);

  // The extractor the Q-networks read: the critic's own, or the one it shares.
  FeaturesExtractorNet& features_extractor() { return shared_ ? *shared_ : extractor_; }
  const FeaturesExtractorNet& features_extractor() const { return shared_ ? *shared_ : extractor_; }
  // SB3's share_features_extractor=True: the Q-networks read `other` (the actor's extractor,
  // that object itself) through th.set_grad_enabled(False) — the critic loss does not train it
  // — and the critic's own extractor is dropped. The state dict still lists it under
  // <prefix>.features_extractor, as SB3's does (the owner loads it). `other` must outlive this
  // critic and any copy of it that shares it.
  void share_features_extractor(FeaturesExtractorNet& other);
  bool owns_features_extractor() const { return shared_ == nullptr; }
  // A copy of a sharing critic made a target: an extractor of its own, a copy of the shared one
  // (SB3 make_critic(features_extractor=None) + load_state_dict).
  void own_features_extractor_copy();

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

  // SB3 forward(obs, actions): Q_i(features(obs), actions) of every critic, each q(i).output()
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
  // The critic loss's backward through critic i's last forward for dL/dQ_i = grad_q:
  // q(i).grads() becomes its gradient; with a learned extractor dL/d(features) is kept for
  // backward_features_extractor. Critics may run this side by side (for_each_critic).
  void zero_grad_and_backward(int i, const Eigen::Ref<const Eigen::MatrixXf>& grad_q);
  // After zero_grad_and_backward of every critic: the extractor's gradient from the sum of the
  // critics' dL/d(features), added in critic order (torch sums them in the autograd graph).
  // Nothing for a flatten extractor.
  void backward_features_extractor();

  // dL/d(actions) through critic i's last forward for dL/dQ_i = grad_q (n_outputs x n):
  // action_dim x n.
  // Input gradient only: an actor loss's backward also fills the critic's .grad in torch, but
  // the critic optimizer's zero_grad() clears it before its next step, so it is never used.
  void action_gradient(int i, const Eigen::Ref<const Eigen::MatrixXf>& grad_q,
                       Eigen::MatrixXf& grad_actions);

  // SB3 state_dict names: <prefix>.qf<i>.<2l>.weight/bias, e.g. critic.qf0.0.weight and
  // critic.qf0.4.weight for net_arch [256, 256] (torch Sequential indices skip activations),
  // and <prefix>.features_extractor.* for a learned extractor.
  void save(const std::string& prefix, TensorMap& tensors) const;
  void load(const std::string& prefix, const TensorMap& tensors);

 private:
  // th.cat([features_extractor(obs), actions], dim=1) into obs_action_.
  void concat_input(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                    const Eigen::Ref<const Eigen::MatrixXf>& actions);

  int obs_dim_ = 0;  // features per observation
  ThreadPool* pool_ = nullptr;
  FeaturesExtractorNet extractor_;
  FeaturesExtractorNet* shared_ = nullptr;  // share_features_extractor: the actor's
  std::vector<SplitMlp> q_;
  Eigen::MatrixXf obs_action_;
  // Learned extractor: each critic's dL/d(input) of its last backward, and their sum over the
  // feature rows.
  std::vector<Eigen::MatrixXf> grad_inputs_;
  Eigen::MatrixXf grad_features_;
};

// SB3 polyak_update(critic.parameters(), critic_target.parameters(), tau), the extractor's too.
void polyak_update(const ContinuousCritic& critic, ContinuousCritic& target, float tau);

}  // namespace rlrun
