#pragma once
// What an on-policy rollout (OnPolicyCollector, on_policy.hpp; SB3's collect_rollouts) asks of
// its policy. The feed-forward ActorCriticPolicy of PPO, A2C, MaskablePPO and TRPO answers from
// the observations alone (FeedForwardRollout below); RecurrentPPO's LSTM policy
// (algos/ppo_recurrent/) also keeps the envs' recurrent states, which episode starts reset.
#include <Eigen/Core>

#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

class RolloutPolicy {
 public:
  virtual ~RolloutPolicy() = default;
  // gSDE (SB3's use_sde): exploration matrices drawn by reset_noise.
  virtual bool use_sde() const = 0;
  virtual void reset_noise(Rng& rng, int n_envs) = 0;
  // Step `step` of the rollout: actions (as sampled, unclipped), values and log-probs for the
  // envs' observations (one column per env). `episode_starts` (1 x n_envs) flags observations
  // that begin an episode; `masks` as ActorCriticPolicy::act.
  virtual void act(int step, const Eigen::MatrixXf& obs, const Eigen::RowVectorXf& episode_starts,
                   Rng& rng, Eigen::MatrixXf& actions, Eigen::RowVectorXf& values,
                   Eigen::RowVectorXf& log_probs, const Eigen::MatrixXf* masks) = 0;
  // V of env `env`'s final observation of an episode its last step truncated (SB3's timeout
  // bootstrap), asked after the step act() chose.
  virtual float terminal_value(const Eigen::MatrixXf& final_obs, int env) = 0;
  // V of the observations after the rollout's last step; `episode_starts` are that step's
  // dones.
  virtual void last_values(const Eigen::MatrixXf& obs, const Eigen::RowVectorXf& episode_starts,
                           Eigen::RowVectorXf& values) = 0;
};

// ActorCriticPolicy as a rollout policy: no memory, episode starts change nothing.
class FeedForwardRollout final : public RolloutPolicy {
 public:
  explicit FeedForwardRollout(ActorCriticPolicy& policy) : policy_(policy) {}

  bool use_sde() const override { return policy_.use_sde(); }
  void reset_noise(Rng& rng, int n_envs) override { policy_.reset_noise(rng, n_envs); }
  void act(int /*step*/, const Eigen::MatrixXf& obs, const Eigen::RowVectorXf& /*episode_starts*/,
           Rng& rng, Eigen::MatrixXf& actions, Eigen::RowVectorXf& values,
           Eigen::RowVectorXf& log_probs, const Eigen::MatrixXf* masks) override {
    policy_.act(obs, rng, false, actions, values, log_probs, masks);
  }
  float terminal_value(const Eigen::MatrixXf& final_obs, int /*env*/) override {
    policy_.predict_values(final_obs, value_);
    return value_(0);
  }
  void last_values(const Eigen::MatrixXf& obs, const Eigen::RowVectorXf& /*episode_starts*/,
                   Eigen::RowVectorXf& values) override {
    policy_.predict_values(obs, values);
  }

 private:
  ActorCriticPolicy& policy_;
  Eigen::RowVectorXf value_;
};

}  // namespace rlrun
