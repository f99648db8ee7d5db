#pragma once
// What DQN, SAC, TQC, TD3 and DDPG share (SB3 common/off_policy_algorithm.py): their common
// hyperparameters and OffPolicyAlgorithm, the base class that holds the replay buffer, runs the
// learning loop and checkpoints what they share. Each algorithm keeps its whole update (train)
// in its own file.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/algos/common/config_checks.hpp"
#include "rlrun/algos/common/episode_stats.hpp"
#include "rlrun/algos/common/features_extractor_net.hpp"
#include "rlrun/algos/common/her_replay_buffer.hpp"
#include "rlrun/algos/common/net_arch.hpp"
#include "rlrun/algos/common/replay_buffer.hpp"
#include "rlrun/algos/common/resumable_algorithm.hpp"
#include "rlrun/algos/common/training_state.hpp"
#include "rlrun/core/config_fields.hpp"
#include "rlrun/env/observation_encoder.hpp"

namespace rlrun {

class VecStepHook;

// SB3 TrainFreq: `train_freq: 4` (steps) or `train_freq: [1, episode]`.
struct TrainFreq {
  int frequency = 1;
  bool episodes = false;  // false: unit is env steps (per env), true: episodes
};
void decode(const ConfigNode& node, TrainFreq& out);
YAML::Node encode(const TrainFreq& value);

// SB3 replay_buffer_kwargs of HerReplayBuffer (stable_baselines3/her/her_replay_buffer.py);
// ignored by the plain ReplayBuffer.
struct ReplayBufferKwargs {
  int n_sampled_goal = 4;                          // virtual transitions per real one
  std::string goal_selection_strategy = "future";  // future, final or episode
  bool copy_info_dict =
      false;  // SB3's option to pass infos to compute_reward; rlrun's don't read them

  template <class V>
  void visit(V& v) {
    v("n_sampled_goal", n_sampled_goal,
      "HER: virtual transitions per real one (her_ratio = 1 - 1 / (n_sampled_goal + 1))",
      in_range(0, 1000));
    v("goal_selection_strategy", goal_selection_strategy,
      "HER: new goals from the episode's future (inclusive), its final state, or anywhere in it",
      OneOf{{"future", "final", "episode"}});
    v("copy_info_dict", copy_info_dict,
      "HER: store infos for compute_reward (SB3 option; rlrun's goal envs do not read infos)");
  }
};

struct OffPolicyConfig {
  int64_t buffer_size = 1000000;  // transitions kept (all envs together)
  int64_t learning_starts = 100;  // env steps of random actions before learning
  int batch_size = 256;           // minibatch size
  double tau = 0.005;             // target network soft-update coefficient (1 = hard copy)
  double gamma = 0.99;            // discount factor
  TrainFreq train_freq;           // collect this many steps/episodes between updates
  int gradient_steps = 1;         // updates after each collection; -1 = as many as env steps
  bool handle_timeout_termination = true;  // bootstrap truncated (time-limit) transitions
  bool optimize_memory_usage = false;      // next observations not stored twice (SB3)
  // SB3 replay_buffer_class: ReplayBuffer, or HerReplayBuffer for goal-conditioned envs.
  std::string replay_buffer_class = "ReplayBuffer";
  ReplayBufferKwargs replay_buffer_kwargs;

  bool her() const { return replay_buffer_class == "HerReplayBuffer"; }

  template <class V>
  void visit(V& v) {
    v("buffer_size", buffer_size, "replay buffer size in transitions", at_least(1));
    v("learning_starts", learning_starts, "env steps with random actions before learning starts",
      non_negative());
    v("batch_size", batch_size, "minibatch size per gradient step", in_range(1, 1e7));
    v("tau", tau, "soft update coefficient for target networks (1 = hard copy)", unit_interval());
    v("gamma", gamma, "discount factor", unit_interval());
    v("train_freq", train_freq, "update every N steps, or [N, episode]");
    v("gradient_steps", gradient_steps,
      "gradient steps per update (-1: as many as steps collected)", at_least(-1));
    v("handle_timeout_termination", handle_timeout_termination,
      "treat time-limit truncation as not done (bootstrap), as SB3");
    v("optimize_memory_usage", optimize_memory_usage,
      "keep each observation once in the replay buffer (half the memory; SB3's option: needs "
      "handle_timeout_termination: false, not with HerReplayBuffer)");
    v("replay_buffer_class", replay_buffer_class,
      "ReplayBuffer, or HerReplayBuffer (Hindsight Experience Replay) for a goal-conditioned env",
      OneOf{{"ReplayBuffer", "HerReplayBuffer"}});
    v("replay_buffer_kwargs", replay_buffer_kwargs,
      "HerReplayBuffer options: n_sampled_goal, goal_selection_strategy");
  }
};

// Off-policy state that persists across learn() calls (and into checkpoints).
struct OffPolicyState {
  // The buffer replay_buffer_class names. Throws std::invalid_argument for HER without a
  // goal-conditioned Dict observation.
  OffPolicyState(const OffPolicyConfig& config, int n_envs, const Space& observation_space,
                 int act_dim);

  std::unique_ptr<ReplayBuffer> buffer;
  HerReplayBuffer* her = nullptr;  // the same buffer when it relabels goals
  // SB3 _last_original_obs: the observations the next stored transition starts from, as the
  // envs gave them (before env.normalize); obs_dim x n_envs.
  Eigen::MatrixXf last_original_obs;
  EpisodeStats episode_stats;
  int64_t episode_num = 0;
  double progress_remaining = 1.0;
  // Set by read_state: the next learn() continues from the restored envs' observations
  // instead of resetting them (SB3 learn(reset_num_timesteps=False) after loading a buffer).
  bool restored = false;
  // The env the last learn() stepped: a learn() on it again continues its episodes (SB3's
  // learn(reset_num_timesteps=False); runtime/run/trainer.hpp's TrainingSession).
  const VecEnv* continued_env = nullptr;

  // Exact resume: the replay buffer, episode statistics and counters.
  void write_state(StateWriter out) const;
  void read_state(const StateReader& in);
};

// What every off-policy algorithm checks of the replay buffer: its memory, and for
// HerReplayBuffer a goal-conditioned observation (Dict with observation, achieved_goal and
// desired_goal of one size).
void check_replay_buffer(ConfigProblems& out, const OffPolicyConfig& config,
                         const AlgorithmSetup& setup);

// The networks of SAC, TQC and TD3 as their checks see them.
struct BoxActorCriticShape {
  NetArchPiQf net_arch;
  int n_critics = 2;
  int actor_outputs = 1;                // the actor's last layer
  int actor_copies = 2;                 // actor, target, acting copy, the second core's activations
  int critic_outputs = 1;               // TQC: n_quantiles
  FeaturesExtractorSettings extractor;  // in front of the actor and of the critic (one each)
  bool share_features_extractor = false;
};

// SAC's, TQC's and TD3's checks: a bounded Box action space, gradient_steps, net_arch, the
// features extractor (SB3's image rules; one for the actor and its copies, one for the critic
// and its target unless shared), the memory of the actor and of n_critics critics with their
// targets, and the replay buffer's.
void check_box_actor_critic(ConfigProblems& out, const AlgorithmSetup& setup,
                            const OffPolicyConfig& config, const BoxActorCriticShape& shape);

// SB3 OffPolicyAlgorithm: the replay buffer (allocated on first use: learn or resume, never for
// a model that is only evaluated) and the stream that samples it; learn(), SB3's learn and
// collect_rollouts: collect `train_freq` steps (or episodes) into the replay buffer, then run
// `gradient_steps` updates once num_timesteps > learning_starts; random actions from the action
// space before learning_starts; logs dumped every `log_interval` finished episodes (SB3's
// default for off-policy algorithms is 4). The algorithm supplies its actions, its update and
// the optional hooks below. The training state for an exact resume is ResumableAlgorithm's
// list: num_timesteps, n_updates, the replay stream and buffer, and what the algorithm adds.
class OffPolicyAlgorithm : public ResumableAlgorithm {
 public:
  std::string id() const override { return id_; }
  void learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) final;

  // SB3 _sample_action: actions for obs (obs_dim x n_envs), `env_actions` for the env and
  // `buffer_actions` as the replay buffer stores them (Box: scaled to [-1, 1]); `warmup`
  // (before learning_starts) asks for uniform samples of the action space.
  virtual void select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                              Eigen::MatrixXf& buffer_actions) = 0;

  int64_t n_updates() const { return n_updates_; }
  // Throws std::bad_optional_access before the first learn() or resume.
  const ReplayBuffer& replay_buffer() const { return *state_.value().buffer; }

 protected:
  // The replay buffer's sampling stream: seed ^ stream, checkpointed under `key`.
  struct ReplayStream {
    uint64_t stream;
    std::string key;
  };
  // `config` and `setup` as the algorithm's constructor validated them (valid_config).
  // normalize_images: the policy's (SB3 preprocess_obs divides image observations by 255 before
  // a flatten extractor; false when a NatureCNN reads the pixels and divides them itself).
  OffPolicyAlgorithm(std::string id, const OffPolicyConfig& config, const AlgorithmSetup& setup,
                     int buffer_action_dim, const ReplayStream& replay, bool normalize_images);

  // SB3 train(gradient_steps, batch_size): `gradient_steps` updates, the means logged.
  virtual void train(int gradient_steps, Logger* logger) = 0;
  // SB3 _on_step, after every VecEnv step (DQN: target update and exploration schedule).
  virtual void on_step(Logger* /*logger*/) {}
  // After each finished episode of env `env` (SB3 collect_rollouts: action_noise.reset).
  virtual void on_episode_end(int /*env*/) {}
  // Before each env step of collect_rollouts, `collected_steps` into it (SAC's gSDE resets).
  virtual void before_collect_step(int64_t /*collected_steps*/) {}
  // What _dump_logs adds for this algorithm (SAC with gSDE: train/std).
  virtual void record_rollout_logs(Logger& /*logger*/) {}

  // replay_buffer.sample(batch_size) with the replay stream, into a reused batch.
  const ReplayBatch& sample_batch();
  // What the networks see of observations: SB3's preprocess_obs and CombinedExtractor for
  // vector keys (env/observation_encoder.hpp). The replay buffer keeps the observations as the
  // env gave them (as SB3's does); each batch and each acting call goes through one of these.
  // For Box, MultiBinary and Dict-of-those observations they hand back the caller's matrix
  // itself (no copy). Each result is valid until the next call of the same encoder.
  int features_dim() const { return acting_obs_.features_dim(); }
  const ObservationEncoder& acting_encoder() const { return acting_obs_; }
  Eigen::Ref<const Eigen::MatrixXf> batch_obs(const ReplayBatch& b) { return batch_obs_(b.obs); }
  Eigen::Ref<const Eigen::MatrixXf> batch_next_obs(const ReplayBatch& b) {
    return batch_next_obs_(b.next_obs);
  }
  Eigen::Ref<const Eigen::MatrixXf> acting_features(const Eigen::Ref<const Eigen::MatrixXf>& obs) {
    return acting_obs_(obs);
  }

  // Training progress, 1 at the start and 0 at the end (SB3 _current_progress_remaining).
  double progress_remaining() const { return state_ ? state_->progress_remaining : 1.0; }

  const AlgorithmSetup setup_;
  int64_t n_updates_ = 0;

 private:
  struct LearnCall;  // one learn() call's clock, hooks and acting workspaces (off_policy.cpp)
  OffPolicyState& state();
  // SB3 collect_rollouts: train_freq steps per env, or train_freq episodes, into the replay
  // buffer. False when a callback stopped training.
  bool collect_rollouts(LearnCall& call);
  // SB3 _dump_logs.
  void dump_logs(LearnCall& call);

  std::string id_;
  OffPolicyConfig config_;
  int buffer_action_dim_;
  Rng replay_rng_;
  std::optional<OffPolicyState> state_;
  ReplayBatch batch_;
  const VecStepHook* step_hook_ = nullptr;  // the training env's VecNormalize, during learn()
  ObservationEncoder batch_obs_, batch_next_obs_, acting_obs_;
};

}  // namespace rlrun
