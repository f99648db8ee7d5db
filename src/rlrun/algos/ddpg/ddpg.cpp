#include "rlrun/algos/ddpg/ddpg.hpp"

namespace rlrun {

TD3::Config DDPG::to_td3(const Config& config) {
  TD3::Config td3;
  td3.learning_rate = config.learning_rate;
  td3.off_policy = config.off_policy;
  td3.action_noise = config.action_noise;
  td3.policy = config.policy;
  // SB3 ddpg.py: "Remove all tricks from TD3 to obtain DDPG". It passes target_policy_noise 0.1
  // only so that TD3 does not complain; with target_noise_clip 0 the smoothing noise is zero.
  td3.policy_delay = 1;
  td3.target_policy_noise = 0.1;
  td3.target_noise_clip = 0.0;
  return td3;
}

DDPG::DDPG(const Config& config, const AlgorithmSetup& setup)
    : td3_(to_td3(config), setup, "DDPG") {}

void DDPG::learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) {
  // Keep this object's counter current during training too: the runtime reads
  // num_timesteps() when it saves best_model.zip or a checkpoint from inside the hooks.
  TrainingHooks inner = hooks;
  inner.on_step = [this, &hooks](int64_t num_timesteps) {
    num_timesteps_ = num_timesteps;
    return !hooks.on_step || hooks.on_step(num_timesteps);
  };
  td3_.learn(env, total_timesteps, inner);
  num_timesteps_ = td3_.num_timesteps();
}

void DDPG::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
                   Eigen::MatrixXf& actions) {
  td3_.predict(obs, deterministic, actions);
}

}  // namespace rlrun
