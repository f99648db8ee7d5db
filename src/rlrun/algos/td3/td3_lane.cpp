#include "rlrun/algos/td3/td3_lane.hpp"

#include "rlrun/algos/td3/td3_target.hpp"

namespace rlrun {

Td3Lane::Td3Lane(int obs_dim, int action_dim, const std::vector<int>& net_arch,
                 Activation activation, int n_critics)
    : obs_dim_(obs_dim),
      action_dim_(action_dim),
      actor_(obs_dim, action_dim, net_arch, activation),
      actor_target_(actor_) {
  critics_.reserve(n_critics);
  for (int i = 0; i < n_critics; ++i)
    critics_.emplace_back(obs_dim + action_dim, net_arch, activation);
  for (const ContinuousCritic& c : critics_) target_values_.push_back(&c.target_values());
}

void Td3Lane::init(Rng& rng) {
  actor_.net().init_torch_default(rng);
  actor_target_.net().params() = actor_.net().params();
  for (ContinuousCritic& c : critics_) c.init(rng);
}

void Td3Lane::pull_critic_pass_params(const Td3Lane& primary) {
  actor_target_.net().params() = primary.actor_target_.net().params();
  for (size_t i = 0; i < critics_.size(); ++i) {
    critics_[i].pull_online(primary.critics_[i]);
    critics_[i].pull_target(primary.critics_[i]);
  }
}

void Td3Lane::pull_actor_pass_params(const Td3Lane& primary) {
  actor_.net().params() = primary.actor_.net().params();
  critics_.front().pull_online(primary.critics_.front());
}

void Td3Lane::resize_workspaces(Eigen::Index count) {
  if (obs_action_.cols() == count) return;
  next_actions_.resize(action_dim_, count);
  grad_q_.resize(1, count);
  for (Eigen::MatrixXf* m : {&obs_action_, &next_obs_action_, &obs_action_pi_})
    m->resize(obs_dim_ + action_dim_, count);
}

double Td3Lane::critic_pass(const ReplayBatch& batch, Eigen::Index begin, Eigen::Index count,
                            const Eigen::MatrixXf& noise, float gamma, float inv_batch,
                            Eigen::MatrixXf& y) {
  resize_workspaces(count);
  // with th.no_grad(): a' = clamp(actor_target(s') + noise, -1, 1), the critics' input
  // th.cat([s', a'], dim=1), and the minimum over the target critics.
  const auto next_obs = batch.next_obs.middleCols(begin, count);
  smoothed_target_actions(actor_target_.forward(next_obs), noise.middleCols(begin, count),
                          next_actions_);
  next_obs_action_.topRows(obs_dim_) = next_obs;
  next_obs_action_.bottomRows(action_dim_) = next_actions_;
  for (ContinuousCritic& c : critics_) c.compute_target_values(next_obs_action_);
  auto y_slice = y.middleCols(begin, count);
  td3_target(target_values_, batch.rewards.segment(begin, count), batch.dones.segment(begin, count),
             gamma, y_slice);

  // critic_loss = sum_i F.mse_loss(Q_i(s, a), y).
  obs_action_.topRows(obs_dim_) = batch.obs.middleCols(begin, count);
  obs_action_.bottomRows(action_dim_) = batch.actions.middleCols(begin, count);
  double loss = 0.0;
  for (ContinuousCritic& c : critics_)
    loss += c.loss_and_gradient(obs_action_, y_slice, inv_batch);
  return loss;
}

double Td3Lane::actor_pass(const ReplayBatch& batch, Eigen::Index begin, Eigen::Index count,
                           float inv_batch) {
  resize_workspaces(count);
  // actor_loss = -critic.q1_forward(s, actor(s)).mean(): through critic 1 into the actor.
  const auto obs = batch.obs.middleCols(begin, count);
  obs_action_pi_.topRows(obs_dim_) = obs;
  obs_action_pi_.bottomRows(action_dim_) = actor_.forward(obs);
  ContinuousCritic& q1 = critics_.front();
  q1.compute_values(obs_action_pi_);
  const double loss = -static_cast<double>(q1.values().sum()) * inv_batch;
  grad_q_.setConstant(-inv_batch);
  q1.compute_action_gradient(grad_q_, action_dim_);
  actor_.net().zero_grad();
  actor_.backward(q1.action_gradient());
  return loss;
}

}  // namespace rlrun
