#include "rlrun/algos/sac/sac.hpp"

#include "rlrun/core/config_validation.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

ConfigProblems SAC::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  // The actor's mean and log std heads; the actor and its acting copy.
  const SacPolicyConfig& p = config.policy;
  check_box_actor_critic(out, setup, config.off_policy,
                         {p.net_arch, p.n_critics, 2 * setup.action_space.flat_dim(), 2, 1,
                          p.extractor(), p.share_features_extractor});
  return out;
}

SAC::SAC(const Config& config, const AlgorithmSetup& setup)
    : EntropyRegularizedActorCritic("SAC", valid_config(config, "SAC"), config.policy, setup,
                                    /*critic_outputs=*/1) {
  grad_min_q_.resize(critic_.n_critics());
  grad_q_.resize(critic_.n_critics());
  grad_critic_actions_.resize(critic_.n_critics());
  critic_losses_.resize(critic_.n_critics());
}

// SB3 sac/sac.py SAC.train, one pass of its loop over gradient steps (CleanRL's
// sac_continuous_action.py has the same update), in the order of Haarnoja et al. 2018b
// (arXiv:1812.05905), Algorithm 1: the critics, the policy, the temperature, the target
// networks. SB3 steps the temperature first; the step uses alpha as it was before that update
// (detached), so the numbers are the same.
EntropyRegularizedStepStats SAC::train_on_batch(const ReplayBatch& b, float lr,
                                                bool update_target) {
  const Eigen::Index n = b.obs.cols();
  const float inv_n = 1.0f / static_cast<float>(n);
  const auto gamma = static_cast<float>(config_.off_policy.gamma);
  EntropyRegularizedStepStats stats;
  // The reparameterisation noise in SB3's order; ent_coef = exp(log_ent_coef.detach()).
  const float alpha = begin_step(n);
  stats.ent_coef = alpha;

  // The soft Bellman target, with th.no_grad():
  //   next_actions, next_log_prob = actor.action_log_prob(next_obs)
  //   next_q = min_i critic_target_i(next_obs, next_actions) - ent_coef * next_log_prob
  //   target_q = rewards + (1 - dones) * gamma * next_q
  const Eigen::Ref<const Eigen::MatrixXf> next_obs = batch_next_obs(b);
  sample_next_actions(next_obs);
  critic_target_.forward(next_obs, next_actions_);
  target_q_.resize(1, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const float next_q = critic_target_.min(j) - alpha * next_log_prob_(j);
    target_q_(0, j) = b.rewards(j) + (1.0f - b.dones(j)) * gamma * next_q;
  }

  // actions_pi, log_prob = actor.action_log_prob(obs). SB3 samples these first; here s' went
  // first because the actor keeps only its last forward pass for the backward below (the
  // noise was drawn in SB3's order, so the numbers are the same).
  const Eigen::Ref<const Eigen::MatrixXf> obs = batch_obs(b);
  sample_policy_actions(obs);

  // The critics: critic_loss = 0.5 * sum_i F.mse_loss(critic_i(obs, actions), target_q); one
  // Adam step. They are independent here: each one's loss, backward and Adam step may run on
  // its own core (ContinuousCritic::for_each_critic); the losses are summed in critic order.
  critic_.forward(obs, b.actions);
  critic_.for_each_critic(n, [&](int i) {
    Eigen::MatrixXf& grad_q = grad_q_[i];
    grad_q = critic_.q(i).output() - target_q_;
    critic_losses_[i] = static_cast<double>(grad_q.squaredNorm()) * (0.5f * inv_n);
    grad_q *= inv_n;  // d critic_loss / d Q_i = (Q_i - target_q) / n
    critic_.zero_grad_and_backward(i, grad_q);
    critic_optimizers_[i].step(lr);
  });
  for (double loss : critic_losses_) stats.critic_loss += loss;
  update_critic_features_extractor(lr);  // CnnPolicy: the critic's NatureCNN, same loss

  // The policy: actor_loss = (ent_coef * log_prob - min_i critic_i(obs, actions_pi)).mean(),
  // through the critics as just stepped (th.min sends the gradient to the smallest).
  critic_.forward(obs, actions_pi_);
  q_pi_.resize(n);
  for (Eigen::MatrixXf& g : grad_min_q_) g.setZero(1, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const int i = critic_.argmin(j);
    q_pi_(j) = critic_.q(i).output()(0, j);
    grad_min_q_[i](0, j) = -inv_n;
  }
  critic_.for_each_critic(
      n, [&](int i) { critic_.action_gradient(i, grad_min_q_[i], grad_critic_actions_[i]); });
  grad_actions_ = grad_critic_actions_[0];
  for (int i = 1; i < critic_.n_critics(); ++i) grad_actions_ += grad_critic_actions_[i];
  stats.actor_loss = update_actor(q_pi_, grad_actions_, alpha, lr);

  // The temperature, towards target_entropy (when learned).
  stats.ent_coef_loss = ent_coef_.update(log_prob_, lr);

  // The target networks.
  if (update_target) update_target_critics();
  return stats;
}

// predict(deterministic): the squashed mean unscaled to the Box; the value is the first
// critic's Q(s, a) of that action.
void SAC::export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const {
  const ExportedAction action = export_action(graph, obs);
  if (with_value)
    graph.set_value(graph.mlp(export_critic_input(graph, action), critic_.q(0).net()));
}

}  // namespace rlrun
