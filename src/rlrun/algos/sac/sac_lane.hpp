#pragma once
// One replica of SAC's networks (the actor, the critics and their targets) that runs the
// forward and backward passes of one slice of a minibatch. SAC splits each training-sized
// minibatch over two lanes, one per core (algos/common/batch_lanes.hpp), and adds the replica's
// gradients to the primary lane's before each optimizer step: the gradient torch computes over
// the whole batch.
//
// A gradient step has two passes with an optimizer step between them (SB3 steps the critics
// before their Q-values enter the actor loss): critic_pass (policy samples, soft Bellman
// target, critic loss) and actor_pass (actor loss through the updated critics). Lane 0 holds
// the trained parameters; a replica lane copies what a pass reads from it first (pull_*). The
// passes write only the lane's own members and their own columns of the shared outputs.
#include <Eigen/Core>
#include <vector>

#include "rlrun/algos/common/continuous_critic.hpp"
#include "rlrun/algos/common/replay_buffer.hpp"
#include "rlrun/algos/sac/sac_actor.hpp"

namespace rlrun {

class SacLane {
 public:
  // Parameters start at zero: call init (primary lane) or pull them (replicas).
  SacLane(int obs_dim, int action_dim, const std::vector<int>& net_arch, Activation activation,
          int n_critics);

  // SB3 SACPolicy._build order: the actor, then each critic (its target a copy); torch's
  // default Linear init (off-policy policies never call init_weights).
  void init(Rng& rng);

  SacActor& actor() { return actor_; }
  const SacActor& actor() const { return actor_; }
  std::vector<ContinuousCritic>& critics() { return critics_; }
  const std::vector<ContinuousCritic>& critics() const { return critics_; }

  // Copies what critic_pass reads (the actor, every critic and critic target) / what
  // actor_pass reads besides critic_pass's actor (the just-stepped critics) from `primary`.
  void pull_critic_pass_params(const SacLane& primary);
  void pull_actor_pass_params(const SacLane& primary);

  // SAC.train's critic part for columns [begin, begin + count) of `batch`, with those columns
  // of the standard-normal noise for s' and s and the entropy coefficient alpha (its value
  // before this step's update): a' ~ pi(s') and a_pi ~ pi(s) (log pi(a_pi|s) -> those columns
  // of log_prob, for the alpha update), y = r + (1 - done) gamma (min_i Q_target_i(s', a') -
  // alpha log pi(a'|s')) -> those columns of y, then each critic's term of
  // 0.5 * sum_i mse(Q_i(s, a), y) with its gradient in q().grads(); inv_batch = 1 / the whole
  // batch size. Returns the slice's part of the critic loss.
  double critic_pass(const ReplayBatch& batch, Eigen::Index begin, Eigen::Index count,
                     const Eigen::MatrixXf& next_noise, const Eigen::MatrixXf& policy_noise,
                     float alpha, float gamma, float inv_batch, Eigen::RowVectorXf& log_prob,
                     Eigen::MatrixXf& y);
  // SAC.train's actor loss mean(alpha log pi(a_pi|s) - min_i Q_i(s, a_pi)) for the same
  // columns, through the critics as they are now (after their step) and pathwise through the
  // squashed Gaussian of critic_pass's sample: returns the slice's part and leaves its gradient
  // in actor().net().grads() (zeroed first).
  double actor_pass(const ReplayBatch& batch, Eigen::Index begin, Eigen::Index count,
                    float alpha, float inv_batch);

 private:
  void resize_workspaces(Eigen::Index count);

  int obs_dim_ = 0;
  int action_dim_ = 0;
  SacActor actor_;
  std::vector<ContinuousCritic> critics_;
  std::vector<const Eigen::MatrixXf*> target_values_, q_values_;
  std::vector<Eigen::MatrixXf> grad_q_;
  Eigen::MatrixXf next_actions_, actions_pi_, grad_actions_;
  Eigen::RowVectorXf next_log_prob_, log_prob_, grad_log_prob_;
  Eigen::MatrixXf obs_action_, next_obs_action_, obs_action_pi_;
};

}  // namespace rlrun
