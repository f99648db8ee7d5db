#pragma once
// rl-baselines3-zoo's search spaces (rl_zoo3/hyperparams_opt.py: sample_ppo_params,
// sample_a2c_params, sample_dqn_params, sample_sac_params, sample_td3_params,
// sample_ddpg_params, sample_tqc_params, sample_her_params), with the same parameter names,
// ranges and conversions (one_minus_gamma -> gamma, net_arch "small" -> [64, 64], gradient_steps
// from train_freq ...), written as rlrun experiment keys.
#include <memory>
#include <string>

#include "rlrun/tune/study_space.hpp"

namespace rlrun::tune {

// The zoo's space for an algorithm id (PPO, A2C, TRPO, ARS, DQN, QRDQN, SAC, TD3, DDPG, TQC), with HER's two
// parameters when the experiment uses HerReplayBuffer. UsageError for an algorithm the zoo has
// no space for.
std::unique_ptr<StudySpace> zoo_space(const std::string& algo_id, bool uses_her);

}  // namespace rlrun::tune
