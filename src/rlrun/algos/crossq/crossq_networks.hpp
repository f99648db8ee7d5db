#pragma once
// sb3-contrib 2.4's CrossQ networks (sb3_contrib/crossq/policies.py): the Actor and the
// CrossQCritic, both MLPs with a BatchRenorm before every Linear (nn/batch_renorm_mlp.hpp) and
// no target copies. Their BatchRenorm layers run in train mode (batch statistics, running
// statistics updated) or eval mode (running statistics) as CrossQ.train switches them with
// set_bn_training_mode; acting and predict() use eval mode (SB3 predict sets
// set_training_mode(False)).
//
// Actor: latent_pi = [BN] Linear act [BN] Linear act ... BN (a trailing BatchRenorm on the last
// hidden layer), then SAC's heads mu and log_std (or gSDE) and the tanh-squashed Gaussian: the
// heads are a SacActor without hidden layers (algos/common/sac_actor.hpp) that reads latent_pi.
// Critic: n_critics Q-networks qf<i> = [BN] Linear act ... [BN] Linear(1) on concat(obs, action).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/algos/common/sac_actor.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/batch_renorm_mlp.hpp"
#include "rlrun/nn/batch_split.hpp"

namespace rlrun {

class PolicyGraph;

// CrossQPolicy's batch_norm options, shared by the actor and the critic.
struct CrossQNorm {
  bool batch_norm = true;
  BatchRenormOptions options;
};

class CrossQActor {
 public:
  CrossQActor() = default;
  CrossQActor(int obs_dim, int action_dim, const std::vector<int>& net_arch, Activation activation,
              const CrossQNorm& norm, const SacActorSde& sde, ThreadPool* pool = nullptr);

  int action_dim() const { return heads_.action_dim(); }
  bool use_sde() const { return heads_.use_sde(); }
  BatchRenormMlp& latent_pi() { return latent_pi_; }
  const BatchRenormMlp& latent_pi() const { return latent_pi_; }
  SacActor& heads() { return heads_; }
  const SacActor& heads() const { return heads_; }

  // torch's default Linear init: latent_pi's layers, then mu and log_std.
  void init(Rng& rng);
  // Every parameter the actor's optimizer steps (gSDE's log_std too).
  std::vector<ParamBlock> blocks();
  // The acting copy's refresh: parameters and running statistics.
  void copy_parameters_from(const CrossQActor& other);
  void reset_noise(Rng& rng, int batch_size) { heads_.reset_noise(rng, batch_size); }
  double mean_std() const { return heads_.mean_std(); }
  void write_state(StateWriter out) const { heads_.write_state(out); }
  void read_state(const StateReader& in) { heads_.read_state(in); }

  // action_log_prob(obs) with latent_pi's BatchRenorm in train or eval mode; SacActor::sample
  // and sample_from_noise after it.
  void sample(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool training, Rng& rng,
              Eigen::MatrixXf& actions, Eigen::RowVectorXf& log_prob);
  void sample_from_noise(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool training,
                         const Eigen::Ref<const Eigen::MatrixXf>& noise, Eigen::MatrixXf& actions,
                         Eigen::RowVectorXf& log_prob);
  // deterministic=True, eval mode.
  void mode(const Eigen::Ref<const Eigen::MatrixXf>& obs, Eigen::MatrixXf& actions);
  // The backward of the last sample: the heads', then latent_pi's (optimizer.zero_grad() first).
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob);

  // mode() as graph nodes: latent_pi in eval mode folded into plain dense layers.
  std::string export_mode(PolicyGraph& graph, const std::string& features) const;

  // <prefix>.latent_pi.<k>.* (BatchRenorm and Linear modules), <prefix>.mu.*,
  // <prefix>.log_std.* (SB3's SAC Actor names for the heads).
  void save(const std::string& prefix, TensorMap& tensors) const;
  void load(const std::string& prefix, const TensorMap& tensors);

 private:
  BatchRenormMlp latent_pi_;
  SacActor heads_;
};

class CrossQCritic {
 public:
  CrossQCritic() = default;
  // Throws std::invalid_argument for n_critics < 1.
  CrossQCritic(int obs_dim, int action_dim, const std::vector<int>& net_arch, Activation activation,
               int n_critics, const CrossQNorm& norm, ThreadPool* pool = nullptr);

  int n_critics() const { return static_cast<int>(q_.size()); }
  BatchRenormMlp& q(int i) { return q_[i]; }
  const BatchRenormMlp& q(int i) const { return q_[i]; }
  void init(Rng& rng);

  // fn(i) for every critic, side by side on the pool when one critic's pass of n columns does
  // not split by itself (as ContinuousCritic::for_each_critic).
  template <class F>
  void for_each_critic(Eigen::Index n, F&& fn) {
    const int critics = n_critics();
    const bool apart = critics > 1 && column_parts(n, q_.front().multiply_adds_per_column()) == 1;
    run_parts(pool_, apart ? 2 : 1, [&](int part) {
      for (int i = apart ? part : 0; i < critics; i += apart ? 2 : 1) fn(i);
    });
  }

  // forward(obs, actions) of every critic with their BatchRenorm in train or eval mode; each
  // q(i).output() is 1 x n.
  void forward(const Eigen::Ref<const Eigen::MatrixXf>& obs,
               const Eigen::Ref<const Eigen::MatrixXf>& actions, bool training);
  // th.min over the critics of column j of the last forward: the first smallest critic.
  int argmin(Eigen::Index j) const;
  // dL/d(actions) through critic i's last (eval-mode) forward for dL/dQ_i = grad_q.
  void action_gradient(int i, const Eigen::Ref<const Eigen::MatrixXf>& grad_q,
                       Eigen::MatrixXf& grad_actions) {
    q_[i].backward_input(grad_q, grad_actions, obs_dim_);
  }

  // <prefix>.qf<i>.<k>.* with torch Sequential indices.
  void save(const std::string& prefix, TensorMap& tensors) const;
  void load(const std::string& prefix, const TensorMap& tensors);

 private:
  int obs_dim_ = 0;
  ThreadPool* pool_ = nullptr;
  std::vector<BatchRenormMlp> q_;
  Eigen::MatrixXf obs_action_;
};

}  // namespace rlrun
