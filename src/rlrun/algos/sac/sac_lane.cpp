#include "rlrun/algos/sac/sac_lane.hpp"

#include "rlrun/algos/sac/sac_loss.hpp"

namespace rlrun {

SacLane::SacLane(int obs_dim, int action_dim, const std::vector<int>& net_arch,
                 Activation activation, int n_critics)
    : obs_dim_(obs_dim),
      action_dim_(action_dim),
      actor_(obs_dim, action_dim, net_arch, activation),
      grad_q_(n_critics) {
  critics_.reserve(n_critics);
  for (int i = 0; i < n_critics; ++i)
    critics_.emplace_back(obs_dim + action_dim, net_arch, activation);
  for (const ContinuousCritic& c : critics_) {
    target_values_.push_back(&c.target_values());
    q_values_.push_back(&c.values());
  }
}

void SacLane::init(Rng& rng) {
  actor_.net().init_torch_default(rng);
  for (ContinuousCritic& c : critics_) c.init(rng);
}

void SacLane::pull_critic_pass_params(const SacLane& primary) {
  actor_.net().params() = primary.actor_.net().params();
  for (size_t i = 0; i < critics_.size(); ++i) {
    critics_[i].pull_online(primary.critics_[i]);
    critics_[i].pull_target(primary.critics_[i]);
  }
}

void SacLane::pull_actor_pass_params(const SacLane& primary) {
  for (size_t i = 0; i < critics_.size(); ++i) critics_[i].pull_online(primary.critics_[i]);
}

void SacLane::resize_workspaces(Eigen::Index count) {
  if (obs_action_.cols() == count) return;
  for (Eigen::MatrixXf* m : {&next_actions_, &actions_pi_, &grad_actions_})
    m->resize(action_dim_, count);
  for (Eigen::RowVectorXf* v : {&next_log_prob_, &log_prob_, &grad_log_prob_}) v->resize(count);
  for (Eigen::MatrixXf* m : {&obs_action_, &next_obs_action_, &obs_action_pi_})
    m->resize(obs_dim_ + action_dim_, count);
  for (Eigen::MatrixXf& g : grad_q_) g.resize(1, count);
}

double SacLane::critic_pass(const ReplayBatch& batch, Eigen::Index begin, Eigen::Index count,
                            const Eigen::MatrixXf& next_noise, const Eigen::MatrixXf& policy_noise,
                            float alpha, float gamma, float inv_batch,
                            Eigen::RowVectorXf& log_prob, Eigen::MatrixXf& y) {
  resize_workspaces(count);
  const auto obs = batch.obs.middleCols(begin, count);
  const auto next_obs = batch.next_obs.middleCols(begin, count);
  // Policy samples for s' (no gradient) and s (kept for actor_pass's backward): the actor's
  // Mlp keeps only its last forward, so s goes second.
  actor_.sample_from_noise(next_obs, next_noise.middleCols(begin, count), next_actions_,
                           next_log_prob_);
  actor_.sample_from_noise(obs, policy_noise.middleCols(begin, count), actions_pi_, log_prob_);
  log_prob.segment(begin, count) = log_prob_;

  // Soft Bellman target from the target critics (th.no_grad()).
  next_obs_action_.topRows(obs_dim_) = next_obs;
  next_obs_action_.bottomRows(action_dim_) = next_actions_;
  for (ContinuousCritic& c : critics_) c.compute_target_values(next_obs_action_);
  auto y_slice = y.middleCols(begin, count);
  sac_critic_target(batch.rewards.segment(begin, count), batch.dones.segment(begin, count),
                    target_values_, next_log_prob_, alpha, gamma, y_slice);

  // critic_loss = 0.5 * sum_i F.mse_loss(Q_i(s, a), y).
  obs_action_.topRows(obs_dim_) = obs;
  obs_action_.bottomRows(action_dim_) = batch.actions.middleCols(begin, count);
  double loss = 0.0;
  for (ContinuousCritic& c : critics_)
    loss += c.loss_and_gradient(obs_action_, y_slice, 0.5f * inv_batch);
  return loss;
}

double SacLane::actor_pass(const ReplayBatch& batch, Eigen::Index begin, Eigen::Index count,
                           float alpha, float inv_batch) {
  // actor_loss = (alpha * log_prob - min_i Q_i(s, a_pi)).mean() with the updated critics:
  // dQ/da through the critics (input gradient only), then pathwise through the squashed
  // Gaussian into the actor.
  obs_action_pi_.topRows(obs_dim_) = batch.obs.middleCols(begin, count);
  obs_action_pi_.bottomRows(action_dim_) = actions_pi_;
  for (ContinuousCritic& c : critics_) c.compute_values(obs_action_pi_);
  const double loss =
      sac_actor_loss(q_values_, log_prob_, alpha, inv_batch, grad_q_, grad_log_prob_);
  for (size_t i = 0; i < critics_.size(); ++i) {
    critics_[i].compute_action_gradient(grad_q_[i], action_dim_);
    if (i == 0) {
      grad_actions_ = critics_[i].action_gradient();
    } else {
      grad_actions_ += critics_[i].action_gradient();
    }
  }
  actor_.net().zero_grad();
  actor_.backward(grad_actions_, grad_log_prob_);
  return loss;
}

}  // namespace rlrun
