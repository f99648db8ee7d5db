#pragma once
// SB3's ReplayBuffer (stable_baselines3/common/buffers.py): preallocated float32 storage of
// `buffer_size` transitions in total, split over the envs (buffer_size / n_envs slots each),
// a circular write position, uniform sampling with replacement using the run's RNG.
// Timeouts as SB3's handle_timeout_termination: a transition that ended by truncation only
// is stored as not-done, so its target bootstraps from next_obs (= the final observation).
#include <Eigen/Core>
#include <cstdint>

#include "rlrun/core/state_dict.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

class VecEnv;

struct ReplayBatch {
  Eigen::MatrixXf obs, next_obs, actions;  // features x batch
  Eigen::RowVectorXf rewards, dones;       // dones: 1 = do not bootstrap
};

class ReplayBuffer {
 public:
  virtual ~ReplayBuffer() = default;
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
  int obs_dim() const { return static_cast<int>(obs_.rows()); }
  int n_envs() const { return n_envs_; }

  // Exact resume (checkpoints): the filled transitions and the write position. Reading
  // refuses a buffer of another capacity (StateMismatch).
  virtual void write_state(StateWriter out) const;
  virtual void read_state(const StateReader& in);

 protected:  // HerReplayBuffer (her_replay_buffer.hpp) relabels these
  // Sizes `batch` for `batch_size` samples (a no-op when it already has that size).
  void size_batch(int batch_size, ReplayBatch& batch) const;

  int64_t slots_;  // per env
  int n_envs_;
  bool handle_timeout_termination_;
  int64_t pos_ = 0;
  bool full_ = false;
  // Column k = slot * n_envs + env.
  Eigen::MatrixXf obs_, next_obs_, actions_;
  Eigen::RowVectorXf rewards_, dones_;
};

}  // namespace rlrun
