#pragma once
// What PPO and A2C share (SB3 common/on_policy_algorithm.py and common/buffers.py
// RolloutBuffer): the rollout buffer, collect_rollouts with timeout bootstrapping and GAE, and
// the learn loop (collect, log, train).
#include <Eigen/Core>
#include <functional>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/episode_stats.hpp"
#include "rlrun/algos/common/gae.hpp"

namespace rlrun {

class PolicyGraph;

// n_steps x n_envs transitions; sample k = step * n_envs + env in the column-major matrices,
// which is also the flat index of the row-major StepEnvMatrix arrays.
struct RolloutBuffer {
  RolloutBuffer(int n_steps, int n_envs, int obs_dim, int act_dim);
  int size() const { return static_cast<int>(obs.cols()); }

  Eigen::MatrixXf obs, actions;  // actions as sampled (before clipping to the Box bounds)
  StepEnvMatrix rewards, values, episode_starts, log_probs, advantages, returns;
};

// The rollout side of an on-policy algorithm; persists across learn() calls.
class OnPolicyCollector {
 public:
  // sde_sample_freq: with a gSDE policy, new exploration matrices every that many steps of a
  // rollout (<= 0: only at the start of each rollout), SB3's sde_sample_freq.
  OnPolicyCollector(const AlgorithmSetup& setup, int n_steps, int act_dim,
                    int sde_sample_freq = -1);

  // SB3 collect_rollouts + compute_returns_and_advantage. Returns false when a callback
  // stopped training. `num_timesteps` counts all envs' steps. A gSDE policy draws its
  // exploration matrices (reset_noise) from rng.
  bool collect(VecEnv& env, ActorCriticPolicy& policy, Rng& rng, float gamma, float gae_lambda,
               TrainingHooks& hooks, int64_t& num_timesteps);
  // Called by learn() at its start: reset the envs, every env starts an episode — unless a
  // training state was just restored, in which case the envs continue where they were.
  void start(VecEnv& env);

  // Resume: last observations, episode-start flags, the episode statistics and the iteration
  // count (SB3 logs every log_interval iterations of one learn() call).
  void write_state(StateWriter out) const;
  void read_state(const StateReader& in);
  int64_t& iterations() { return iterations_; }

  RolloutBuffer& buffer() { return buffer_; }
  const RolloutBuffer& buffer() const { return buffer_; }
  EpisodeStats& episode_stats() { return episode_stats_; }

 private:
  Space action_space_;
  RolloutBuffer buffer_;
  EpisodeStats episode_stats_;
  bool restored_ = false;
  int64_t iterations_ = 0;
  int sde_sample_freq_ = -1;
  Eigen::MatrixXf last_obs_, step_actions_, env_actions_, final_obs_;
  Eigen::RowVectorXf last_episode_starts_, step_values_, step_log_probs_, terminal_value_;
};

// SB3 Box handling in on-policy rollouts: actions are clipped to the bounds before env.step
// (the buffer keeps the unclipped sample, whose log-prob was computed).
void clip_to_box(const Space& space, Eigen::MatrixXf& actions);
// The same as graph nodes (nn/policy_graph.hpp); `actions` unchanged for other spaces.
std::string export_clip_to_box(PolicyGraph& graph, const Space& space, const std::string& actions);

// SB3 OnPolicyAlgorithm.learn: until total_timesteps: collect, update progress, dump logs every
// log_interval iterations (before train, as SB3), train.
void on_policy_learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks,
                     OnPolicyCollector& collector, int64_t& num_timesteps,
                     const std::function<bool()>& collect,
                     const std::function<void(double progress_remaining)>& train);

}  // namespace rlrun
