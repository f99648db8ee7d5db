#include "rlrun/algos/trpo/trpo.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "rlrun/algos/common/explained_variance.hpp"
#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/algos/ppo/ppo_loss.hpp"
#include "rlrun/algos/trpo/conjugate_gradient.hpp"
#include "rlrun/core/config_validation.hpp"

namespace rlrun {

ConfigProblems TRPO::check(const Config& config, const AlgorithmSetup& setup) {
  const int64_t rollout = static_cast<int64_t>(config.n_steps) * setup.n_envs;
  ConfigProblems out = check_actor_critic(config.policy, rollout,
                                          std::min<int64_t>(config.batch_size, rollout), setup);
  // sb3-contrib trpo.py asserts n_steps * n_envs > 1: advantages are normalised.
  if (config.normalize_advantage && rollout < 2)
    out.push_back({"n_steps", "n_steps * n_envs must be > 1 to normalise advantages"});
  if (config.policy.features_extractor_class != FeaturesExtractor::kFlatten &&
      config.policy.features_extractor_class != FeaturesExtractor::kCombined)
    out.push_back({"policy.features_extractor_class",
                   "TRPO is built for MlpPolicy and MultiInputPolicy without images: its "
                   "Fisher-vector product does not run through a CNN yet"});
  check_use_sde(out, config.use_sde, setup);
  return out;
}

TRPO::TRPO(const Config& config, const AlgorithmSetup& setup)
    : OnPolicyAlgorithm("TRPO", setup, valid_config(config, "TRPO").policy,
                        {config.n_steps, config.gamma, config.gae_lambda, config.use_sde,
                         config.sde_sample_freq}),
      config_(config),
      rng_(setup.seed ^ kSampleStream) {
  if (policy_.features_extractor().learned())
    throw std::invalid_argument(
        "TRPO: images need a CNN, and TRPO's Fisher-vector product does not run through one "
        "yet (MlpPolicy and MultiInputPolicy without images are built)");
  // SB3 ActorCriticPolicy: Adam with eps=1e-5 over every parameter; the actor's never have a
  // gradient when it steps (set to None in sb3-contrib), so torch's Adam leaves them alone.
  AdamConfig adam;
  adam.eps = 1e-5;
  critic_optimizer_ = Adam(policy_.critic_blocks(), adam);
  checkpoint("optimizer", critic_optimizer_);
  checkpoint("shuffle_rng", rng_);
  indices_.resize(static_cast<size_t>(config_.n_steps) * setup.n_envs);
}

void TRPO::train(double progress_remaining, Logger* logger) {
  const float lr = static_cast<float>(config_.learning_rate(progress_remaining));
  const RolloutBuffer& rollout = collector_.buffer();

  // The policy batch: rollout_buffer.get(batch_size=None), a shuffled copy of the whole
  // rollout, then every sub_sampling_factor-th sample.
  shuffle();
  const int n = (rollout.size() + config_.sub_sampling_factor - 1) / config_.sub_sampling_factor;
  batch_obs_.resize(rollout.obs.rows(), n);
  batch_act_.resize(rollout.actions.rows(), n);
  batch_adv_.resize(n);
  batch_old_logp_.resize(n);
  for (int j = 0; j < n; ++j) {
    const int k = indices_[static_cast<size_t>(j) * config_.sub_sampling_factor];
    rollout.obs.get(k, batch_obs_.col(j).data());
    batch_act_.col(j) = rollout.actions.col(k);
    batch_adv_(j) = rollout.advantages.data()[k];
    batch_old_logp_(j) = rollout.log_probs.data()[k];
  }
  if (config_.normalize_advantage) normalize_advantages(batch_adv_);

  double objective = 0, kl = 0;
  bool success = false;
  update_actor(objective, kl, success);
  const double value_loss = update_critic(lr);
  ++n_updates_;

  if (!logger) return;
  logger->record("train/learning_rate", lr);
  logger->record("train/policy_objective", objective);
  logger->record("train/value_loss", value_loss);
  logger->record("train/kl_divergence_loss", kl);
  logger->record("train/explained_variance",
                 explained_variance(rollout.values.reshaped<Eigen::RowMajor>(),
                                    rollout.returns.reshaped<Eigen::RowMajor>()));
  logger->record("train/is_line_search_success", success ? 1.0 : 0.0);
  if (policy_.gaussian()) logger->record("train/std", policy_.mean_std());
  logger->record("train/n_updates", static_cast<double>(n_updates_));
}

void TRPO::update_actor(double& objective, double& kl, bool& success) {
  // 1. The surrogate (advantages * ratio).mean() and its gradient at the old parameters, where
  //    the ratio is one: d/dlog_prob = advantages * ratio / n.
  policy_.evaluate_actions(batch_obs_, batch_act_, values_, log_prob_, entropy_);
  const ActionDistributionParams old_distribution = policy_.distribution();
  objective = surrogate();
  const Eigen::Index n = log_prob_.size();
  grad_log_prob_ =
      (batch_adv_.array() * (log_prob_ - batch_old_logp_).array().exp() / static_cast<float>(n))
          .matrix();
  grad_values_.setZero(n);
  grad_entropy_.setZero(n);
  policy_.zero_grad();
  policy_.backward(grad_values_, grad_log_prob_, grad_entropy_);
  Eigen::VectorXf objective_gradient;
  policy_.get_actor_grads(objective_gradient);

  // 2. s = (F + damping I)^-1 g by conjugate gradient (sb3-contrib hessian_vector_product).
  const float damping = static_cast<float>(config_.cg_damping);
  auto fisher = [&](const Eigen::VectorXf& v, Eigen::VectorXf& out) {
    policy_.fisher_vector_product(v, out);
    out += damping * v;
  };
  const Eigen::VectorXf direction =
      conjugate_gradient(fisher, objective_gradient, config_.cg_max_steps, rng_);

  // 3. Backtracking from the step whose quadratic KL model equals target_kl.
  Eigen::VectorXf product;
  fisher(direction, product);
  const float max_step =
      std::sqrt(2.0f * static_cast<float>(config_.target_kl) / direction.dot(product));
  Eigen::VectorXf original;
  policy_.get_actor_params(original);
  float coefficient = 1.0f;
  success = false;
  for (int i = 0; i < config_.line_search_max_iter && !success; ++i) {
    policy_.set_actor_params(original + (coefficient * max_step) * direction);
    policy_.evaluate_actions(batch_obs_, batch_act_, values_, log_prob_, entropy_);
    const double new_objective = surrogate();
    const double new_kl = policy_.mean_kl(old_distribution);
    if (new_kl < config_.target_kl && new_objective > objective) {
      success = true;
      objective = new_objective;
      kl = new_kl;
    }
    coefficient *= static_cast<float>(config_.line_search_shrinking_factor);
  }
  if (!success) {
    policy_.set_actor_params(original);
    kl = 0.0;
  }
}

double TRPO::update_critic(float lr) {
  const RolloutBuffer& rollout = collector_.buffer();
  const int size = rollout.size();
  double loss_sum = 0;
  int minibatches = 0;
  for (int epoch = 0; epoch < config_.n_critic_updates; ++epoch) {
    shuffle();
    for (int start = 0; start < size; start += config_.batch_size) {
      const int batch = std::min(config_.batch_size, size - start);
      mb_obs_.resize(rollout.obs.rows(), batch);
      mb_ret_.resize(batch);
      for (int j = 0; j < batch; ++j) {
        const int k = indices_[start + j];
        rollout.obs.get(k, mb_obs_.col(j).data());
        mb_ret_(j) = rollout.returns.data()[k];
      }
      // F.mse_loss(returns, values): d/dV = 2 (V - R) / batch.
      policy_.predict_values(mb_obs_, values_);
      grad_values_ = (2.0f / static_cast<float>(batch)) * (values_ - mb_ret_);
      loss_sum += (values_ - mb_ret_).squaredNorm() / batch;
      ++minibatches;
      policy_.zero_grad();
      policy_.backward_values(grad_values_);
      critic_optimizer_.step(lr);
    }
  }
  // np.mean of an empty list is nan (n_critic_updates 0).
  return minibatches ? loss_sum / minibatches : std::nan("");
}

void TRPO::shuffle() {
  const int size = static_cast<int>(indices_.size());
  std::iota(indices_.begin(), indices_.end(), 0);
  for (int i = size - 1; i > 0; --i)
    std::swap(indices_[i], indices_[static_cast<int>(rng_.below(i + 1))]);
}

double TRPO::surrogate() const {
  return (batch_adv_.array() * (log_prob_ - batch_old_logp_).array().exp()).cast<double>().mean();
}

}  // namespace rlrun
