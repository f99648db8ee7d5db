#pragma once
// SB3's ReplayBuffer (stable_baselines3/common/buffers.py): preallocated storage of
// `buffer_size` transitions in total, split over the envs (buffer_size / n_envs slots each),
// a circular write position, uniform sampling with replacement using the run's RNG.
// Observations keep their space's dtype (uint8 images as bytes, observation_columns.hpp).
// Timeouts as SB3's handle_timeout_termination: a transition that ended by truncation only
// is stored as not-done, so its target bootstraps from next_obs (= the final observation).
// optimize_memory_usage as SB3's: no next_obs copy; a transition's next observation is the
// following slot's observation (add() writes it there until the next add() overwrites it with
// the observation after a reset), so the transition being written is never sampled, and an
// episode's final observation is lost — which only a done transition has, and a done one does
// not bootstrap; SB3 therefore refuses it with handle_timeout_termination, and so does rlrun.
#include <Eigen/Core>
#include <cstdint>

#include "rlrun/algos/common/observation_columns.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class VecEnv;

struct ReplayBatch {
  Eigen::MatrixXf obs, next_obs, actions;  // features x batch
  Eigen::RowVectorXf rewards, dones;       // dones: 1 = do not bootstrap
};

class ReplayBuffer {
 public:
  virtual ~ReplayBuffer() = default;
  // Throws std::invalid_argument for optimize_memory_usage with handle_timeout_termination, or
  // with fewer than two slots per env.
  ReplayBuffer(int64_t buffer_size, int n_envs, const Space& observation_space, int act_dim,
               bool handle_timeout_termination = true, bool optimize_memory_usage = false);
  // Float32 observations of obs_dim values.
  ReplayBuffer(int64_t buffer_size, int n_envs, int obs_dim, int act_dim,
               bool handle_timeout_termination = true);

  // Stores one VecEnv step taken from `obs` with `buffer_actions`; next observations, rewards
  // and flags are read from `env` (final_obs for envs whose episode ended): the original ones,
  // before a VecNormalize step hook (SB3 stores VecNormalize's originals), and `obs` must be
  // the original observations too.
  virtual void add(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                   const Eigen::Ref<const Eigen::MatrixXf>& buffer_actions, const VecEnv& env);
  // Fills `batch` (resized once per batch size) with `batch_size` uniform samples.
  virtual void sample(int batch_size, Rng& rng, ReplayBatch& batch) const;

  int64_t size() const { return (full_ ? slots_ : pos_) * n_envs_; }
  int64_t capacity() const { return slots_ * n_envs_; }
  int obs_dim() const { return obs_.rows(); }
  int n_envs() const { return n_envs_; }

  // Exact resume (checkpoints): the filled transitions and the write position. Reading
  // refuses a buffer of another capacity (StateMismatch).
  virtual void write_state(StateWriter out) const;
  virtual void read_state(const StateReader& in);

 protected:  // HerReplayBuffer (her_replay_buffer.hpp) relabels these
  // Sizes `batch` for `batch_size` samples (a no-op when it already has that size).
  void size_batch(int batch_size, ReplayBatch& batch) const;

  // The column of the transition after column k's in the same env (optimize_memory_usage).
  int64_t following(int64_t k) const { return (k / n_envs_ + 1) % slots_ * n_envs_ + k % n_envs_; }
  // Columns of obs_ holding observations (with optimize_memory_usage, one slot past size()).
  int64_t stored_observations() const;
  // Copies transition column k into column j of `batch`.
  void copy_transition(int64_t k, int j, ReplayBatch& batch) const;

  int64_t slots_;  // per env
  int n_envs_;
  bool handle_timeout_termination_;
  bool optimize_memory_usage_;
  int64_t pos_ = 0;
  bool full_ = false;
  // Column k = slot * n_envs + env. next_obs_ has no columns with optimize_memory_usage.
  ObservationColumns obs_, next_obs_;
  Eigen::MatrixXf actions_;
  Eigen::RowVectorXf rewards_, dones_;
};

}  // namespace rlrun
