#pragma once
// The algorithm interface (SB3's BaseAlgorithm, reduced to what the runtime needs).
// An algorithm is built from its Config and the env's spaces; learn() trains it on a VecEnv;
// predict() maps observations to env-ready actions (clipped to the action space) for
// evaluation and recording; save/load move every tensor in and out of the model file.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include "rlrun/core/logger.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class VecEnv;
class PolicyGraph;
class ThreadPool;

struct AlgorithmSetup {
  Space observation_space;
  Space action_space;
  int n_envs = 1;
  uint64_t seed = 0;
  // The run's threads (core/thread_pool.hpp), which the update's parts share; null: the
  // calling thread alone. Never changes a result (nn/batch_split.hpp).
  ThreadPool* pool = nullptr;
};

// What learn() reports to and asks of the runtime.
struct TrainingHooks {
  Logger* logger = nullptr;
  // Called after every VecEnv step with the total env steps so far; false stops training
  // (SB3's callback.on_step()).
  std::function<bool(int64_t num_timesteps)> on_step;
  // Called where SB3 calls callback.on_rollout_end(): after a rollout was collected, before
  // the update that learns from it (on-policy: before train(); off-policy: before the
  // gradient steps of the round; ARS: after evaluating its candidates, as sb3-contrib's evaluate_candidates).
  std::function<void(int64_t num_timesteps)> on_rollout_end;
  // Called after each log dump (console progress bar, etc.).
  std::function<void(int64_t num_timesteps)> on_log;
  // Called where learn() can stop and later resume exactly (after each train(): on-policy
  // once per iteration, off-policy once per collect-and-train round). The runtime writes
  // checkpoints here; false stops training (Ctrl-C waits for this point so that the checkpoint
  // it writes resumes exactly).
  std::function<bool(int64_t num_timesteps)> at_safe_point;
  // SB3's learn(log_interval=...): dump logs every N iterations (on-policy) or N episodes
  // (off-policy); 0 = the algorithm's SB3 default (1 on-policy, 4 off-policy).
  int log_interval = 0;
};

class Algorithm {
 public:
  virtual ~Algorithm() = default;
  virtual std::string id() const = 0;

  // Trains until num_timesteps() >= total_timesteps (counting all envs' steps, like SB3).
  virtual void learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) = 0;

  // obs: obs_dim x batch. actions: resized to act_dim x batch, valid for the env.
  virtual void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
                       Eigen::MatrixXf& actions) = 0;

  // Invalid-action masking (env/action_mask.hpp; sb3-contrib's MaskablePPO): the entries of one
  // observation's mask that predict_masked() takes; 0 when the algorithm takes no masks.
  virtual int action_mask_size() const { return 0; }
  // Whether evaluation and recording pass the env's masks to predict_masked() (MaskablePPO's
  // use_masking).
  virtual bool masks_from_env() const { return false; }
  // predict() with `masks` (action_mask_size() x batch, 0/1): masked actions are never chosen.
  // Throws std::invalid_argument for masks of another shape, entries other than 0/1 or no
  // legal action.
  virtual void predict_masked(const Eigen::Ref<const Eigen::MatrixXf>& /*obs*/,
                              const Eigen::Ref<const Eigen::MatrixXf>& /*masks*/,
                              bool /*deterministic*/, Eigen::MatrixXf& /*actions*/) {
    throw std::logic_error(id() + " takes no action masks");
  }

  // Recurrent policies (sb3-contrib's RecurrentPPO): the floats of one observation's recurrent
  // state (0: the policy has none). predict_recurrent() is predict() that carries `states`
  // (recurrent_state_size() x batch, in and out; zeros to begin with) from call to call,
  // zeroing an observation's state first where `episode_starts` is 1 (sb3-contrib's
  // predict(obs, state, episode_start)).
  virtual int recurrent_state_size() const { return 0; }
  // The LSTM layers the state holds: its rows are every layer's h, then every layer's c, each
  // recurrent_state_size() / (2 * layers) floats (torch's (num_layers, n, hidden) pair).
  virtual int recurrent_layers() const { return 0; }
  virtual void predict_recurrent(const Eigen::Ref<const Eigen::MatrixXf>& /*obs*/,
                                 const Eigen::Ref<const Eigen::RowVectorXf>& /*episode_starts*/,
                                 Eigen::MatrixXf& /*states*/, bool /*deterministic*/,
                                 Eigen::MatrixXf& /*actions*/) {
    throw std::logic_error(id() + " has no recurrent state");
  }

  virtual void save(TensorMap& tensors) const = 0;
  // Throws std::runtime_error when a tensor is missing or has another shape.
  virtual void load(const TensorMap& tensors) = 0;

  // Exact resume: everything learn() needs beyond save()'s tensors to continue as if it had
  // never stopped — optimizer moments, RNG streams, counters, buffers, the last observations.
  // Valid at a safe point (TrainingHooks::at_safe_point) or before the first learn(). After
  // load_training_state, learn() continues with the env as restored, without resetting it.
  virtual void save_training_state(StateWriter& /*out*/) const {
    throw std::logic_error(id() + " cannot save its training state for resume yet");
  }
  virtual void load_training_state(const StateReader& /*in*/) {
    throw std::logic_error(id() + " cannot restore a training state yet");
  }

  // Deploying (rlrun export; nn/policy_graph.hpp): appends to `graph` the deterministic
  // predict() as nodes, from `obs` (the flat observations predict() takes) to the actions it
  // returns, and sets graph.set_action(). With `with_value` also graph.set_value(): the critic's
  // V(s) (PPO, A2C), the Q-values of every action (DQN), the first critic's Q(s, a) of the
  // action taken (SAC, TD3, DDPG), or the mean of every critic's quantiles there (TQC). Throws ExportError when the algorithm cannot be exported.
  virtual void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const;

  int64_t num_timesteps() const { return num_timesteps_; }

 protected:
  int64_t num_timesteps_ = 0;
};

}  // namespace rlrun
