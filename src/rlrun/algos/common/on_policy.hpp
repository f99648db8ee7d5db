#pragma once
// What PPO and A2C share (SB3 common/on_policy_algorithm.py and common/buffers.py
// RolloutBuffer): the rollout buffer, collect_rollouts with timeout bootstrapping and GAE, and
// OnPolicyAlgorithm, the base class that holds the actor-critic policy, runs the learn loop
// (collect, log, train), acts, saves and checkpoints what they share. Each algorithm keeps its
// whole update (train) in its own file.
#include <Eigen/Core>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/episode_stats.hpp"
#include "rlrun/algos/common/gae.hpp"
#include "rlrun/algos/common/observation_columns.hpp"
#include "rlrun/algos/common/resumable_algorithm.hpp"
#include "rlrun/algos/common/rollout_policy.hpp"
#include "rlrun/env/action_mask.hpp"

namespace rlrun {

class PolicyGraph;

// n_steps x n_envs transitions; sample k = step * n_envs + env in the column-major matrices,
// which is also the flat index of the row-major StepEnvMatrix arrays.
// Observations keep their space's dtype (uint8 images as bytes; SB3's RolloutBuffer holds
// float32, so an image rollout here takes a quarter of its memory).
// With mask_size > 0 it is sb3-contrib's MaskableRolloutBuffer (common/maskable/buffers.py):
// each sample also keeps the action mask its action was drawn under.
struct RolloutBuffer {
  RolloutBuffer(int n_steps, int n_envs, const Space& observation_space, int act_dim,
                int mask_size = 0);
  int size() const { return static_cast<int>(actions.cols()); }

  ObservationColumns obs;
  Eigen::MatrixXf actions;       // actions as sampled (before clipping to the Box bounds)
  Eigen::MatrixXf action_masks;  // mask_size x size, 0/1 (empty without masking)
  StepEnvMatrix rewards, values, episode_starts, log_probs, advantages, returns;
};

// The rollout side of an on-policy algorithm; persists across learn() calls.
class OnPolicyCollector {
 public:
  // sde_sample_freq: with a gSDE policy, new exploration matrices every that many steps of a
  // rollout (<= 0: only at the start of each rollout), SB3's sde_sample_freq. mask_size > 0:
  // sb3-contrib MaskablePPO's collect_rollouts, which reads every step's action masks from the
  // envs (env/action_mask.hpp; an env without them is an error, as sb3-contrib's "Environment
  // does not support action masking"), acts with them and keeps them in the buffer.
  OnPolicyCollector(const AlgorithmSetup& setup, int n_steps, int act_dim, int sde_sample_freq = -1,
                    int mask_size = 0);

  // SB3 collect_rollouts + compute_returns_and_advantage. Returns false when a callback
  // stopped training. `num_timesteps` counts all envs' steps. A gSDE policy draws its
  // exploration matrices (reset_noise) from rng.
  bool collect(VecEnv& env, RolloutPolicy& policy, Rng& rng, float gamma, float gae_lambda,
               TrainingHooks& hooks, int64_t& num_timesteps);
  // Called by learn() at its start: reset the envs, every env starts an episode — unless a
  // training state was just restored, in which case the envs continue where they were.
  void start(VecEnv& env);

  // Resume: last observations, episode-start flags, the episode statistics and the iteration
  // count (SB3 logs every log_interval iterations of one learn() call); with masking the last
  // observations' masks, checked on reading (shape, 0/1, a legal action) as untrusted data.
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
  // The env the last learn() stepped: a learn() on it again continues its episodes (SB3's
  // learn(reset_num_timesteps=False); runtime/run/trainer.hpp's TrainingSession).
  const VecEnv* continued_env_ = nullptr;
  int64_t iterations_ = 0;
  int sde_sample_freq_ = -1;
  int mask_size_ = 0;
  std::vector<ActionMaskReader> mask_readers_;  // one per env copy
  Eigen::MatrixXf last_masks_;                  // the masks of last_obs_ (mask_size x n_envs)
  Eigen::MatrixXf last_obs_, step_actions_, env_actions_, final_obs_;
  Eigen::RowVectorXf last_episode_starts_, step_values_, step_log_probs_, terminal_value_;
};

// SB3 Box handling in on-policy rollouts: actions are clipped to the bounds before env.step
// (the buffer keeps the unclipped sample, whose log-prob was computed).
void clip_to_box(const Space& space, Eigen::MatrixXf& actions);
// The same as graph nodes (nn/policy_graph.hpp); `actions` unchanged for other spaces.
std::string export_clip_to_box(PolicyGraph& graph, const Space& space, const std::string& actions);

// SB3 OnPolicyAlgorithm: the policy (ActorCriticPolicy, built from the seed), the rollout
// collector and its action stream; learn(): until total_timesteps, collect a rollout, dump
// logs every log_interval iterations (before train, as SB3), train; predict() and the export
// act with the policy's mode or a sample, clipped to a Box; save()/load() move the policy's
// tensors. The training state for an exact resume is ResumableAlgorithm's list:
// num_timesteps, n_updates, the action stream, the collector and gSDE's exploration matrices,
// and what the algorithm adds (its optimizer, PPO's shuffling stream).
class OnPolicyAlgorithm : public ResumableAlgorithm {
 public:
  std::string id() const override { return id_; }
  void learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) final;
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions) override;
  // Masks (a maskable policy): the masked distribution's mode or a sample.
  int action_mask_size() const final { return policy_.mask_size(); }
  bool masks_from_env() const final { return env_masks_; }
  void predict_masked(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                      const Eigen::Ref<const Eigen::MatrixXf>& masks, bool deterministic,
                      Eigen::MatrixXf& actions) final;
  // predict(deterministic): the policy's mode, clipped to a Box; the value is the critic's V(s).
  // A maskable policy exports its unmasked mode (the graph takes no masks; docs/deploy.md).
  void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const override;
  void save(TensorMap& tensors) const override { policy_.save(tensors); }
  void load(const TensorMap& tensors) override { policy_.load(tensors); }

  const ActorCriticPolicy& policy() const { return policy_; }
  // The last rollout's rewards (after timeout bootstrapping) and values, n_steps x n_envs.
  const StepEnvMatrix& rollout_rewards() const { return collector_.buffer().rewards; }
  const StepEnvMatrix& rollout_values() const { return collector_.buffer().values; }

 protected:
  // What the base needs of the algorithm's Config (each algorithm has its own defaults).
  struct Rollout {
    int n_steps;  // steps per env per rollout
    double gamma, gae_lambda;
    bool use_sde;
    int sde_sample_freq;
  };
  // `setup` and the settings as the algorithm's constructor validated them (valid_config).
  // `maskable`: the masked policy of sb3-contrib's MaskablePPO; `env_masks` (with it): its
  // rollouts and evaluations read the env's masks (learn(use_masking=True)).
  OnPolicyAlgorithm(std::string id, const AlgorithmSetup& setup,
                    const ActorCriticPolicyConfig& policy, const Rollout& rollout,
                    bool maskable = false, bool env_masks = false);
  // RecurrentPPO (algos/ppo_recurrent/): policy_ holds only the towers and heads, built on
  // `policy_input` (a Box of the LSTM's width), and rollouts run through rollout_policy().
  OnPolicyAlgorithm(std::string id, const AlgorithmSetup& setup, const Space& policy_input,
                    const ActorCriticPolicyConfig& policy, const Rollout& rollout);

  // What the rollouts act with: policy_ itself unless an algorithm puts layers in front of it.
  virtual RolloutPolicy& rollout_policy() { return feed_forward_; }

  // One update on the rollout just collected (collector_.buffer()), SB3 train(); records its
  // train/ values on `logger` if any.
  virtual void train(double progress_remaining, Logger* logger) = 0;

  const AlgorithmSetup setup_;
  ActorCriticPolicy policy_;
  OnPolicyCollector collector_;
  int64_t n_updates_ = 0;
  Rng action_rng_;  // collection samples and predict()

 private:
  // The training state's items (ResumableAlgorithm::checkpoint), once per constructor.
  void register_state();

  FeedForwardRollout feed_forward_{policy_};
  std::string id_;
  bool env_masks_ = false;
  float gamma_, gae_lambda_;
  Eigen::RowVectorXf predict_values_, predict_log_probs_;
  Eigen::MatrixXf predict_masks_;
};

}  // namespace rlrun
