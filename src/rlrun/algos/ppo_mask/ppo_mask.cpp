#include "rlrun/algos/ppo_mask/ppo_mask.hpp"

#include "rlrun/core/config_validation.hpp"

namespace rlrun {

PPO::Config MaskablePPO::ppo_config(const Config& config) {
  PPO::Config ppo;
  ppo.learning_rate = config.learning_rate;
  ppo.n_steps = config.n_steps;
  ppo.batch_size = config.batch_size;
  ppo.n_epochs = config.n_epochs;
  ppo.gamma = config.gamma;
  ppo.gae_lambda = config.gae_lambda;
  ppo.clip_range = config.clip_range;
  ppo.clip_range_vf = config.clip_range_vf;
  ppo.normalize_advantage = config.normalize_advantage;
  ppo.ent_coef = config.ent_coef;
  ppo.vf_coef = config.vf_coef;
  ppo.max_grad_norm = config.max_grad_norm;
  ppo.use_sde = false;
  ppo.target_kl = config.target_kl;
  ppo.policy = config.policy;
  return ppo;
}

// As PPO's (sb3-contrib keeps SB3's assertion that advantages are normalised over a minibatch).
ConfigProblems MaskablePPO::check(const Config& config, const AlgorithmSetup& setup) {
  return PPO::check(ppo_config(config), setup);
}

MaskablePPO::MaskablePPO(const Config& config, const AlgorithmSetup& setup)
    : PPO("MaskablePPO", ppo_config(valid_config(config, "MaskablePPO")), setup,
          Masking{/*maskable=*/true, config.use_masking}) {}

}  // namespace rlrun
