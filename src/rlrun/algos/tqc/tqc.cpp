#include "rlrun/algos/tqc/tqc.hpp"

#include <stdexcept>

#include "rlrun/algos/common/config_checks.hpp"
#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/algos/common/training_state.hpp"
#include "rlrun/algos/tqc/quantile_huber_loss.hpp"
#include "rlrun/algos/tqc/truncated_quantiles.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

namespace {
// SAC's streams (rng_streams.hpp: kTrainStream, kPredictStream), so a TQC and a SAC run with
// one seed start from the same draws.

void fill_normal(Rng& rng, Eigen::Index rows, Eigen::Index cols, Eigen::MatrixXf& m) {
  m.resize(rows, cols);
  for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = static_cast<float>(rng.normal());
}

SacActorSde actor_sde(const TQC::Config& config) {
  SacActorSde sde;
  sde.use_sde = config.use_sde;
  sde.log_std_init = static_cast<float>(config.policy.log_std_init);
  sde.full_std = config.policy.full_std;
  sde.use_expln = config.policy.use_expln;
  sde.clip_mean = static_cast<float>(config.policy.clip_mean);
  return sde;
}

std::string drop_problem(const TQC::Config& config) {
  const int drop = config.top_quantiles_to_drop_per_net, n = config.policy.n_quantiles;
  if (drop >= 0 && drop < n) return "";
  return "must be in [0, policy.n_quantiles - 1] = [0, " + std::to_string(n - 1) + "], got " +
         std::to_string(drop) + " (the target needs at least one atom per network)";
}
}  // namespace

ConfigProblems TQC::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  // check_box_actor_critic's checks, with critics of n_quantiles outputs.
  check_box_actor_spaces(out, setup);
  check_gradient_steps(out, config.off_policy.gradient_steps);
  const NetArchPiQf& arch = config.policy.net_arch;
  check_net_arch(out, "policy.net_arch", arch.pi, arch.qf);
  const int obs = network_input_dim(out, setup.observation_space);
  const int act = setup.action_space.flat_dim();
  // The actor's mean and log std heads; the actor and its acting copy.
  check_network_memory(out, "policy.net_arch", obs, arch.pi, 2 * act, 2,
                       config.off_policy.batch_size);
  // Each critic, its target and the second core's activations of both.
  check_network_memory(out, "policy.net_arch", obs + act, arch.qf, config.policy.n_quantiles,
                       4 * config.policy.n_critics, config.off_policy.batch_size);
  check_replay_buffer(out, config.off_policy, setup);
  if (const std::string p = drop_problem(config); !p.empty())
    out.push_back({"top_quantiles_to_drop_per_net", p});
  return out;
}

TQC::TQC(const Config& config, const AlgorithmSetup& setup)
    : OffPolicyAlgorithm("TQC", config.off_policy, setup,
                         BoxActionSelection::checked_action_dim(setup, "TQC"),
                         {kSampleStream, "sample_rng"}),
      config_(config),
      action_dim_(setup.action_space.flat_dim()),
      train_rng_(setup.seed ^ kTrainStream),
      predict_rng_(setup.seed ^ kPredictStream),
      actor_(features_dim(), action_dim_, config.policy.net_arch.pi, config.policy.activation_fn,
             actor_sde(config)),
      critic_(features_dim(), action_dim_, config.policy.net_arch.qf, config.policy.activation_fn,
              config.policy.n_critics, config.policy.n_quantiles),
      critic_target_(critic_),
      ent_coef_(config.ent_coef, config.target_entropy, action_dim_),
      acting_(setup, config.action_noise) {
  if (config.target_update_interval < 1)
    throw std::invalid_argument("TQC: target_update_interval must be >= 1");
  if (const std::string p = drop_problem(config); !p.empty())
    throw std::invalid_argument("TQC: top_quantiles_to_drop_per_net " + p);
  // TQCPolicy._build: the actor, then the critic (the target a copy), torch's default Linear
  // init for all; Adam with torch's eps 1e-8 everywhere.
  Rng init_rng(setup.seed);
  actor_.net().init_torch_default(init_rng);
  if (config.use_sde) {
    actor_.reset_noise(init_rng, 1);
    acting_actor_.get().reset_noise(init_rng, 1);
  }
  critic_.init(init_rng);
  critic_target_ = critic_;
  if (config.use_sde)
    actor_optimizer_ = Adam({actor_.net().block(), actor_.sde().block()});
  else
    actor_optimizer_ = Adam({actor_.net().block()});
  for (int i = 0; i < critic_.n_critics(); ++i)
    critic_optimizers_.emplace_back(std::vector<ParamBlock>{critic_.q(i).net().block()});
  // Resume: as SAC's (the networks, targets included, are in the model tensors).
  checkpoint("train_rng", train_rng_);
  checkpoint("predict_rng", predict_rng_);
  checkpoint("acting", acting_);
  checkpoint("actor_optimizer", actor_optimizer_);
  for (int i = 0; i < critic_.n_critics(); ++i)
    checkpoint("critic_optimizer" + std::to_string(i), critic_optimizers_[i]);
  checkpoint("ent_coef", ent_coef_);
  if (config.use_sde) {
    checkpoint("actor_noise", actor_);
    checkpoint("acting_actor_noise", acting_actor_.get());
  }
}

int TQC::n_target_quantiles() const {
  return critic_.n_critics() * (critic_.n_outputs() - config_.top_quantiles_to_drop_per_net);
}

void TQC::before_collect_step(int64_t collected_steps) {
  if (!config_.use_sde) return;
  // SB3 collect_rollouts (SAC::before_collect_step): reset_noise(n_envs) at the start, then
  // whenever num_collected_steps % sde_sample_freq == 0.
  SacActor& acting = acting_actor_.get();
  if (collected_steps == 0) acting.reset_noise(acting_.action_rng(), setup_.n_envs);
  if (config_.sde_sample_freq > 0 && collected_steps % config_.sde_sample_freq == 0)
    acting.reset_noise(acting_.action_rng(), setup_.n_envs);
}

void TQC::record_rollout_logs(Logger& logger) {
  if (config_.use_sde) logger.record("train/std", actor_.mean_std());
}

// sb3-contrib tqc/tqc.py TQC.train, one pass of its loop over gradient steps.
EntropyRegularizedStepStats TQC::train_on_batch(const ReplayBatch& b, float lr, bool update_target) {
  const Eigen::Index n = b.obs.cols();
  const float inv_n = 1.0f / static_cast<float>(n);
  const auto gamma = static_cast<float>(config_.off_policy.gamma);
  const int n_critics = critic_.n_critics();
  const int n_quantiles = critic_.n_outputs();
  EntropyRegularizedStepStats stats;
  if (config_.use_sde) {
    // "We need to sample because `log_std` may have changed between two gradient steps".
    actor_.reset_noise(train_rng_, 1);
  } else {
    // The reparameterisation noise in sb3-contrib's order: for the actions at s, then at s'.
    fill_normal(train_rng_, action_dim_, n, policy_noise_);
    fill_normal(train_rng_, action_dim_, n, next_noise_);
  }
  // ent_coef = exp(log_ent_coef.detach()) (or the fixed value), as it was before this step's
  // update: the target and the actor loss both use it.
  const float alpha = ent_coef_.value();
  stats.ent_coef = alpha;

  // with th.no_grad():
  //   next_actions, next_log_prob = actor.action_log_prob(next_obs)
  //   next_quantiles = critic_target(next_obs, next_actions)    # batch x nets x quantiles
  //   next_quantiles = sort(next_quantiles.reshape(batch, -1))[:, :n_target_quantiles]
  //   target_quantiles = next_quantiles - ent_coef * next_log_prob
  //   target_quantiles = rewards + (1 - dones) * gamma * target_quantiles
  // (sb3-contrib samples the actions at s first; the actor keeps only its last forward pass
  // for the backward below, so s' goes first here, with the noise drawn in sb3-contrib's order:
  // the same numbers.)
  const Eigen::Ref<const Eigen::MatrixXf> next_obs = batch_next_obs(b);
  if (config_.use_sde)
    actor_.sample(next_obs, train_rng_, next_actions_, next_log_prob_);
  else
    actor_.sample_from_noise(next_obs, next_noise_, next_actions_, next_log_prob_);
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

  // actions_pi, log_prob = actor.action_log_prob(obs)
  const Eigen::Ref<const Eigen::MatrixXf> obs = batch_obs(b);
  if (config_.use_sde)
    actor_.sample(obs, train_rng_, actions_pi_, log_prob_);
  else
    actor_.sample_from_noise(obs, policy_noise_, actions_pi_, log_prob_);

  // ent_coef_loss = -(log_ent_coef * (log_prob + target_entropy).detach()).mean(); one Adam
  // step on log_ent_coef, whose gradient is -mean(log_prob + target_entropy).
  if (ent_coef_.learned()) {
    const double shifted = static_cast<double>(log_prob_.mean()) + ent_coef_.target_entropy();
    stats.ent_coef_loss = -static_cast<double>(ent_coef_.log_value()) * shifted;
    ent_coef_.log_ent_coef().grad(0) = static_cast<float>(-shifted);
    ent_coef_.optimizer().step(lr);
  }

  // current_quantiles = critic(obs, actions)
  // critic_loss = quantile_huber_loss(current_quantiles, target_quantiles,
  //                                   sum_over_quantiles=False)   # mean over all atom pairs
  // One Adam step.
  critic_.forward(obs, b.actions);
  const float scale = inv_n / static_cast<float>(n_critics * n_quantiles *
                                                 static_cast<int>(target_quantiles_.rows()));
  for (int i = 0; i < n_critics; ++i) {
    stats.critic_loss +=
        quantile_huber_loss(critic_.q(i).output(), target_quantiles_, scale, grad_quantiles_,
                            pair_loss_);
    critic_.q(i).zero_grad_and_backward(grad_quantiles_);
  }
  for (Adam& optimizer : critic_optimizers_) optimizer.step(lr);

  // qf_pi = critic(obs, actions_pi).mean(dim=2).mean(dim=1)   # every atom of every critic
  // actor_loss = (ent_coef * log_prob - qf_pi).mean(), through the critics as just stepped and
  // pathwise through the squashed Gaussian; one Adam step.
  critic_.forward(obs, actions_pi_);
  const float inv_atoms = 1.0f / static_cast<float>(n_critics * n_quantiles);
  double actor_loss = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    float qf_pi = 0.0f;
    for (int i = 0; i < n_critics; ++i) qf_pi += critic_.q(i).output().col(j).sum();
    actor_loss += static_cast<double>(alpha * log_prob_(j) - qf_pi * inv_atoms);
  }
  stats.actor_loss = actor_loss * static_cast<double>(inv_n);
  // d actor_loss / d Q_ik(s_j) = -1 / (n * n_critics * n_quantiles) for every atom.
  grad_quantiles_.setConstant(n_quantiles, n, -inv_n * inv_atoms);
  for (int i = 0; i < n_critics; ++i) {
    critic_.action_gradient(i, grad_quantiles_, i == 0 ? grad_actions_ : grad_critic_actions_);
    if (i > 0) grad_actions_ += grad_critic_actions_;
  }
  grad_log_prob_.setConstant(n, alpha * inv_n);
  actor_.backward(grad_actions_, grad_log_prob_);
  actor_optimizer_.step(lr);
  acting_actor_.invalidate();

  // polyak_update(critic.parameters(), critic_target.parameters(), tau)
  if (update_target)
    polyak_update(critic_, critic_target_, static_cast<float>(config_.off_policy.tau));
  return stats;
}

void TQC::train(int gradient_steps, Logger* logger) {
  // SB3 _update_learning_rate: one scheduled lr for the actor, critic and ent_coef optimizers.
  const auto lr = static_cast<float>(config_.learning_rate(progress_remaining()));
  train_entropy_regularized(gradient_steps, config_.target_update_interval, lr, ent_coef_.learned(),
                            n_updates_, logger, [&](bool update_target) {
                              return train_on_batch(sample_batch(), lr, update_target);
                            });
}

void TQC::select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                         Eigen::MatrixXf& buffer_actions) {
  // SB3 _sample_action: uniform samples before learning_starts unless gSDE acts at warmup.
  acting_.select(
      obs, warmup && !(config_.use_sde && config_.use_sde_at_warmup),
      [&](Rng& rng, Eigen::MatrixXf& actions) {
        acting_actor_.get().sample(acting_features(obs), rng, actions, acting_log_prob_);
      },
      env_actions, buffer_actions);
}

// predict(deterministic): the squashed mean unscaled to the Box. The value is TQC's estimate
// of Q(s, a) for that action, the mean of every critic's atoms (what the actor maximises).
void TQC::export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const {
  const std::string features = acting_encoder().export_to(graph, obs);
  const std::string scaled = actor_.export_mode(graph, features);
  graph.set_action(acting_.export_env_actions(graph, scaled));
  if (!with_value) return;
  const std::string input = graph.concat({features, scaled});
  std::vector<std::string> atoms;
  for (int i = 0; i < critic_.n_critics(); ++i) atoms.push_back(graph.mlp(input, critic_.q(i).net()));
  const int total = critic_.n_critics() * critic_.n_outputs();
  graph.set_value(graph.dense(graph.concat(atoms),
                              Eigen::MatrixXf::Constant(1, total, 1.0f / static_cast<float>(total)),
                              Eigen::VectorXf::Zero(1)));
}

void TQC::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
                  Eigen::MatrixXf& actions) {
  if (deterministic)
    acting_actor_.get().mode(acting_features(obs), scaled_actions_);
  else
    acting_actor_.get().sample(acting_features(obs), predict_rng_, scaled_actions_,
                                acting_log_prob_);
  acting_.to_env_actions(scaled_actions_, actions);
}

void TQC::save(TensorMap& tensors) const {
  actor_.save("actor", tensors);
  critic_.save("critic", tensors);
  critic_target_.save("critic_target", tensors);
  ent_coef_.save(tensors);
}

void TQC::load(const TensorMap& tensors) {
  actor_.load("actor", tensors);
  critic_.load("critic", tensors);
  critic_target_.load("critic_target", tensors);
  ent_coef_.load(tensors);
  acting_actor_.invalidate();
}

}  // namespace rlrun
