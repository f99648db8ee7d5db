#include "rlrun/algos/ppo/ppo.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "rlrun/algos/common/explained_variance.hpp"
#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/algos/ppo/ppo_loss.hpp"
#include "rlrun/core/config_validation.hpp"
#include "rlrun/nn/clip_grad.hpp"

namespace rlrun {

ConfigProblems PPO::check(const Config& config, const AlgorithmSetup& setup) {
  const int64_t rollout = static_cast<int64_t>(config.n_steps) * setup.n_envs;
  ConfigProblems out = check_actor_critic(config.policy, rollout,
                                          std::min<int64_t>(config.batch_size, rollout), setup);
  // SB3 ppo.py asserts buffer_size > 1: advantages are normalised over a minibatch.
  if (config.normalize_advantage && rollout < 2)
    out.push_back({"n_steps", "n_steps * n_envs must be > 1 to normalise advantages"});
  check_use_sde(out, config.use_sde, setup);
  return out;
}

PPO::PPO(const Config& config, const AlgorithmSetup& setup)
    : PPO("PPO", valid_config(config, "PPO"), setup, Masking{}) {}

PPO::PPO(std::string id, const Config& config, const AlgorithmSetup& setup, Masking masking)
    : OnPolicyAlgorithm(
          std::move(id), setup, config.policy,
          {config.n_steps, config.gamma, config.gae_lambda, config.use_sde, config.sde_sample_freq},
          masking.maskable, masking.use_masking),
      config_(config),
      masking_(masking),
      shuffle_rng_(setup.seed ^ kSampleStream) {
  // SB3 ActorCriticPolicy: Adam with eps=1e-5 "to avoid NaN".
  AdamConfig adam;
  adam.eps = 1e-5;
  optimizer_ = Adam(policy_.param_blocks(), adam);
  checkpoint("optimizer", optimizer_);
  checkpoint("shuffle_rng", shuffle_rng_);

  const int obs_dim = setup.observation_space.flat_dim();
  const int size = config_.n_steps * setup.n_envs;
  indices_.resize(size);
  const int batch = std::min(config_.batch_size, size);
  mb_obs_.resize(obs_dim, batch);
  mb_act_.resize(policy_.action_dim(), batch);
  mb_masks_.resize(masking_.use_masking ? policy_.mask_size() : 0, batch);
  for (Eigen::RowVectorXf* v : {&mb_adv_, &mb_ret_, &mb_old_logp_, &mb_old_val_, &values_pred_,
                                &grad_values_, &grad_log_prob_, &grad_entropy_})
    v->resize(batch);
}

void PPO::train(double progress_remaining, Logger* logger) {
  const float lr = static_cast<float>(config_.learning_rate(progress_remaining));
  const float clip_range = static_cast<float>(config_.clip_range(progress_remaining));
  std::optional<float> clip_range_vf;
  if (config_.clip_range_vf)
    clip_range_vf = static_cast<float>((*config_.clip_range_vf)(progress_remaining));
  const float ent_coef = static_cast<float>(config_.ent_coef);
  const float vf_coef = static_cast<float>(config_.vf_coef);
  const int size = static_cast<int>(indices_.size());

  PpoTrainStatistics statistics;
  bool continue_training = true;
  std::vector<ParamBlock> blocks = policy_.param_blocks();

  for (int epoch = 0; epoch < config_.n_epochs && continue_training; ++epoch) {
    statistics.start_epoch();
    // np.random.permutation: Fisher-Yates with the run's RNG.
    std::iota(indices_.begin(), indices_.end(), 0);
    for (int i = size - 1; i > 0; --i)
      std::swap(indices_[i], indices_[static_cast<int>(shuffle_rng_.below(i + 1))]);

    for (int start = 0; start < size; start += config_.batch_size) {
      gather_minibatch(start, std::min(config_.batch_size, size - start));
      // MaskablePPO: evaluate_actions(..., action_masks=rollout_data.action_masks); with
      // use_masking false no masks are stored (sb3-contrib's action_masks of ones).
      policy_.evaluate_actions(mb_obs_, mb_act_, values_pred_, log_prob_, entropy_,
                               masking_.use_masking ? &mb_masks_ : nullptr);

      if (config_.normalize_advantage) normalize_advantages(mb_adv_);
      const PpoLossTerms t =
          ppo_loss({values_pred_, log_prob_, entropy_, mb_old_logp_, mb_old_val_, mb_adv_, mb_ret_},
                   clip_range, clip_range_vf, ent_coef, vf_coef, grad_values_, grad_log_prob_,
                   grad_entropy_);
      statistics.add(t);

      if (config_.target_kl && t.approx_kl > 1.5 * *config_.target_kl) {
        continue_training = false;
        break;
      }
      policy_.zero_grad();
      policy_.backward(grad_values_, grad_log_prob_, grad_entropy_);
      clip_grad_norm(blocks, static_cast<float>(config_.max_grad_norm));
      optimizer_.step(lr);
    }
    if (!masking_.maskable) ++n_updates_;
  }
  // sb3-contrib ppo_mask.py: `self._n_updates += self.n_epochs` after the loop, also when
  // target_kl stopped it early (SB3's PPO counts the epochs run).
  if (masking_.maskable) n_updates_ += config_.n_epochs;

  if (logger)
    record_ppo_statistics(*logger, statistics, collector_.buffer(), policy_, n_updates_, lr,
                          clip_range, clip_range_vf);
}

void PPO::gather_minibatch(int start, int batch) {
  const RolloutBuffer& rollout = collector_.buffer();
  if (mb_obs_.cols() != batch) {
    mb_obs_.resize(Eigen::NoChange, batch);
    mb_act_.resize(Eigen::NoChange, batch);
    mb_masks_.resize(Eigen::NoChange, batch);
    for (Eigen::RowVectorXf* v : {&mb_adv_, &mb_ret_, &mb_old_logp_, &mb_old_val_, &values_pred_,
                                  &grad_values_, &grad_log_prob_, &grad_entropy_})
      v->resize(batch);
  }
  // Columns copied as raw blocks: Eigen's per-column assignment of a run-time size (3 floats
  // for Pendulum) costs more than the copy. Observations come out of their storage as floats.
  const Eigen::Index obs_rows = rollout.obs.rows(), act_rows = rollout.actions.rows();
  const Eigen::Index mask_rows = mb_masks_.rows();
  for (int j = 0; j < batch; ++j) {
    const int k = indices_[start + j];
    rollout.obs.get(k, mb_obs_.data() + j * obs_rows);
    std::copy_n(rollout.actions.data() + k * act_rows, act_rows, mb_act_.data() + j * act_rows);
    std::copy_n(rollout.action_masks.data() + k * mask_rows, mask_rows,
                mb_masks_.data() + j * mask_rows);
    mb_adv_(j) = rollout.advantages.data()[k];
    mb_ret_(j) = rollout.returns.data()[k];
    mb_old_logp_(j) = rollout.log_probs.data()[k];
    mb_old_val_(j) = rollout.values.data()[k];
  }
}

}  // namespace rlrun
