#include "rlrun/algos/common/replay_buffer.hpp"

#include <algorithm>
#include <stdexcept>

#include "rlrun/core/state_dict.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

ReplayBuffer::ReplayBuffer(int64_t buffer_size, int n_envs, int obs_dim, int act_dim,
                           bool handle_timeout_termination)
    : slots_(std::max<int64_t>(buffer_size / n_envs, 1)),
      n_envs_(n_envs),
      handle_timeout_termination_(handle_timeout_termination) {
  if (buffer_size < 1) throw std::invalid_argument("buffer_size must be >= 1");
  const int64_t columns = slots_ * n_envs_;
  obs_.resize(obs_dim, columns);
  next_obs_.resize(obs_dim, columns);
  actions_.resize(act_dim, columns);
  rewards_.resize(columns);
  dones_.resize(columns);
}

void ReplayBuffer::add(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                       const Eigen::Ref<const Eigen::MatrixXf>& buffer_actions, const VecEnv& env) {
  for (int e = 0; e < n_envs_; ++e) {
    const int64_t k = pos_ * n_envs_ + e;
    obs_.col(k) = obs.col(e);
    // SB3 _store_transition: the next observation of a finished episode is its final one;
    // under VecNormalize the original observations and rewards are stored (batches are
    // normalised when sampled, with the statistics of that time).
    next_obs_.col(k) = env.done(e) ? env.original_final_obs().col(e) : env.original_obs().col(e);
    actions_.col(k) = buffer_actions.col(e);
    rewards_(k) = static_cast<float>(env.original_rewards()(e));
    const bool done = env.terminated(e) || env.truncated(e);
    const bool timeout = env.truncated(e) && !env.terminated(e);
    dones_(k) = (done && !(handle_timeout_termination_ && timeout)) ? 1.0f : 0.0f;
  }
  if (++pos_ == slots_) {
    full_ = true;
    pos_ = 0;
  }
}

void ReplayBuffer::size_batch(int batch_size, ReplayBatch& batch) const {
  if (batch.obs.cols() == batch_size) return;
  batch.obs.resize(obs_.rows(), batch_size);
  batch.next_obs.resize(obs_.rows(), batch_size);
  batch.actions.resize(actions_.rows(), batch_size);
  batch.rewards.resize(batch_size);
  batch.dones.resize(batch_size);
}

void ReplayBuffer::sample(int batch_size, Rng& rng, ReplayBatch& batch) const {
  const int64_t upper = full_ ? slots_ : pos_;
  if (upper == 0) throw std::logic_error("ReplayBuffer::sample on an empty buffer");
  size_batch(batch_size, batch);
  for (int j = 0; j < batch_size; ++j) {
    // SB3: batch_inds = randint(0, upper_bound); env_indices = randint(0, n_envs).
    const int64_t slot = static_cast<int64_t>(rng.below(static_cast<uint64_t>(upper)));
    const int64_t env = n_envs_ > 1 ? static_cast<int64_t>(rng.below(n_envs_)) : 0;
    const int64_t k = slot * n_envs_ + env;
    batch.obs.col(j) = obs_.col(k);
    batch.next_obs.col(j) = next_obs_.col(k);
    batch.actions.col(j) = actions_.col(k);
    batch.rewards(j) = rewards_(k);
    batch.dones(j) = dones_(k);
  }
}

void ReplayBuffer::write_state(StateWriter out) const {
  // Only the filled columns: a checkpoint early in a 1e6-transition run stays small.
  const int64_t used = size();
  put_matrix(out, "obs", obs_.leftCols(used));
  put_matrix(out, "next_obs", next_obs_.leftCols(used));
  put_matrix(out, "actions", actions_.leftCols(used));
  put_matrix(out, "rewards", rewards_.head(used).transpose());
  put_matrix(out, "dones", dones_.head(used).transpose());
  out.put_int("pos", pos_);
  out.put_bool("full", full_);
  out.put_int("capacity", capacity());
}

void ReplayBuffer::read_state(const StateReader& in) {
  if (in.get_int("capacity") != capacity())
    throw StateMismatch("checkpoint replay buffer holds " + std::to_string(in.get_int("capacity")) +
                        " transitions, this run's buffer_size gives " + std::to_string(capacity()));
  pos_ = in.get_int_in("pos", 0, slots_ - 1);
  full_ = in.get_int_in("full", 0, 1) != 0;
  const int64_t used = size();
  get_matrix(in, "obs", obs_.leftCols(used));
  get_matrix(in, "next_obs", next_obs_.leftCols(used));
  get_matrix(in, "actions", actions_.leftCols(used));
  Eigen::VectorXf column(used);
  get_matrix(in, "rewards", column);
  rewards_.head(used) = column.transpose();
  get_matrix(in, "dones", column);
  dones_.head(used) = column.transpose();
}

}  // namespace rlrun
