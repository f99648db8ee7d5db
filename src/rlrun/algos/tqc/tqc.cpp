#include "rlrun/algos/tqc/tqc.hpp"

#include <stdexcept>

#include "rlrun/algos/common/config_checks.hpp"
#include "rlrun/algos/common/quantile_huber_loss.hpp"
#include "rlrun/algos/tqc/truncated_quantiles.hpp"
#include "rlrun/core/config_validation.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

namespace {
std::string drop_problem(const TQC::Config& config) {
  const int drop = config.top_quantiles_to_drop_per_net, n = config.policy.n_quantiles;
  if (drop >= 0 && drop < n) return "";
  return "must be in [0, policy.n_quantiles - 1] = [0, " + std::to_string(n - 1) + "], got " +
         std::to_string(drop) + " (the target needs at least one atom per network)";
}
}  // namespace

ConfigProblems TQC::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  // The actor's mean and log std heads, the actor and its acting copy; critics of n_quantiles
  // outputs.
  const auto& policy = config.policy;
  check_box_actor_critic(out, setup, config.off_policy,
                         {policy.net_arch, policy.n_critics, 2 * setup.action_space.flat_dim(), 2,
                          policy.n_quantiles, policy.extractor(), policy.share_features_extractor});
  if (const std::string p = drop_problem(config); !p.empty())
    out.push_back({"top_quantiles_to_drop_per_net", p});
  return out;
}

TQC::TQC(const Config& config, const AlgorithmSetup& setup)
    : EntropyRegularizedActorCritic("TQC", valid_config(config, "TQC"), config.policy, setup,
                                    /*critic_outputs=*/config.policy.n_quantiles),
      top_quantiles_to_drop_per_net_(config.top_quantiles_to_drop_per_net) {
  if (const std::string p = drop_problem(config); !p.empty())
    throw std::invalid_argument("TQC: top_quantiles_to_drop_per_net " + p);
}

int TQC::n_target_quantiles() const {
  return critic_.n_critics() * (critic_.n_outputs() - top_quantiles_to_drop_per_net_);
}

// sb3-contrib tqc/tqc.py TQC.train, one pass of its loop over gradient steps, in SAC's order
// (sac.cpp): the truncated target and the critics (Kuznetsov et al. 2020, section 4), the
// policy through the critics as just stepped, the temperature, the target networks.
// sb3-contrib steps the temperature first; the step uses alpha as it was before that update
// (detached), so the numbers are the same.
EntropyRegularizedStepStats TQC::train_on_batch(const ReplayBatch& b, float lr,
                                                bool update_target) {
  const Eigen::Index n = b.obs.cols();
  const float inv_n = 1.0f / static_cast<float>(n);
  const auto gamma = static_cast<float>(config_.off_policy.gamma);
  const int n_critics = critic_.n_critics();
  const int n_quantiles = critic_.n_outputs();
  EntropyRegularizedStepStats stats;
  // The reparameterisation noise in sb3-contrib's order; ent_coef = exp(log_ent_coef.detach()).
  const float alpha = begin_step(n);
  stats.ent_coef = alpha;

  // The truncated target, with th.no_grad():
  //   next_actions, next_log_prob = actor.action_log_prob(next_obs)
  //   next_quantiles = critic_target(next_obs, next_actions)    # batch x nets x quantiles
  //   next_quantiles = sort(next_quantiles.reshape(batch, -1))[:, :n_target_quantiles]
  //   target_quantiles = next_quantiles - ent_coef * next_log_prob
  //   target_quantiles = rewards + (1 - dones) * gamma * target_quantiles
  const Eigen::Ref<const Eigen::MatrixXf> next_obs = batch_next_obs(b);
  sample_next_actions(next_obs);
  critic_target_.forward(next_obs, next_actions_);
  next_quantiles_.clear();
  for (int i = 0; i < n_critics; ++i) next_quantiles_.push_back(&critic_target_.q(i).output());
  truncated_quantiles(next_quantiles_, n_target_quantiles(), target_quantiles_, pooled_);
  for (Eigen::Index j = 0; j < n; ++j) {
    const float bootstrap = (1.0f - b.dones(j)) * gamma;
    for (Eigen::Index t = 0; t < target_quantiles_.rows(); ++t)
      target_quantiles_(t, j) =
          b.rewards(j) + bootstrap * (target_quantiles_(t, j) - alpha * next_log_prob_(j));
  }

  // actions_pi, log_prob = actor.action_log_prob(obs) (sb3-contrib samples these first; s'
  // went first as in sac.cpp, with the noise drawn in sb3-contrib's order: the same numbers).
  const Eigen::Ref<const Eigen::MatrixXf> obs = batch_obs(b);
  sample_policy_actions(obs);

  // The critics: current_quantiles = critic(obs, actions)
  // critic_loss = quantile_huber_loss(current_quantiles, target_quantiles,
  //                                   sum_over_quantiles=False)   # mean over all atom pairs
  // One Adam step.
  critic_.forward(obs, b.actions);
  const float scale = inv_n / static_cast<float>(n_critics * n_quantiles *
                                                 static_cast<int>(target_quantiles_.rows()));
  for (int i = 0; i < n_critics; ++i) {
    stats.critic_loss += quantile_huber_loss(critic_.q(i).output(), target_quantiles_, scale,
                                             grad_quantiles_, pair_loss_);
    critic_.zero_grad_and_backward(i, grad_quantiles_);
  }
  for (Adam& optimizer : critic_optimizers_) optimizer.step(lr);
  update_critic_features_extractor(lr);  // CnnPolicy: the critic's NatureCNN, same loss

  // The policy: qf_pi = critic(obs, actions_pi).mean(dim=2).mean(dim=1)   # every atom
  // actor_loss = (ent_coef * log_prob - qf_pi).mean(), through the critics as just stepped.
  critic_.forward(obs, actions_pi_);
  const float inv_atoms = 1.0f / static_cast<float>(n_critics * n_quantiles);
  q_pi_.resize(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    float qf_pi = 0.0f;
    for (int i = 0; i < n_critics; ++i) qf_pi += critic_.q(i).output().col(j).sum();
    q_pi_(j) = qf_pi * inv_atoms;
  }
  // d actor_loss / d Q_ik(s_j) = -1 / (n * n_critics * n_quantiles) for every atom.
  grad_quantiles_.setConstant(n_quantiles, n, -inv_n * inv_atoms);
  for (int i = 0; i < n_critics; ++i) {
    critic_.action_gradient(i, grad_quantiles_, i == 0 ? grad_actions_ : grad_critic_actions_);
    if (i > 0) grad_actions_ += grad_critic_actions_;
  }
  stats.actor_loss = update_actor(q_pi_, grad_actions_, alpha, lr);

  // The temperature, towards target_entropy (when learned).
  stats.ent_coef_loss = ent_coef_.update(log_prob_, lr);

  // The target networks.
  if (update_target) update_target_critics();
  return stats;
}

// The value: the mean of every critic's atoms at (s, the deterministic action).
void TQC::export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const {
  const ExportedAction action = export_action(graph, obs);
  if (!with_value) return;
  const std::string input = export_critic_input(graph, action);
  std::vector<std::string> atoms;
  for (int i = 0; i < critic_.n_critics(); ++i)
    atoms.push_back(graph.mlp(input, critic_.q(i).net()));
  const int total = critic_.n_critics() * critic_.n_outputs();
  graph.set_value(graph.dense(graph.concat(atoms),
                              Eigen::MatrixXf::Constant(1, total, 1.0f / static_cast<float>(total)),
                              Eigen::VectorXf::Zero(1)));
}

}  // namespace rlrun
