#include "rlrun/algos/common/replay_buffer.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "rlrun/core/state_dict.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

ReplayBuffer::ReplayBuffer(int64_t buffer_size, int n_envs, const Space& observation_space,
                           int act_dim, bool handle_timeout_termination, bool optimize_memory_usage)
    : slots_(std::max<int64_t>(buffer_size / n_envs, 1)),
      n_envs_(n_envs),
      handle_timeout_termination_(handle_timeout_termination),
      optimize_memory_usage_(optimize_memory_usage) {
  if (buffer_size < 1) throw std::invalid_argument("buffer_size must be >= 1");
  if (optimize_memory_usage && handle_timeout_termination)
    throw std::invalid_argument(  // SB3 ReplayBuffer.__init__'s ValueError
        "optimize_memory_usage and handle_timeout_termination cannot both be true (the replay "
        "buffer keeps no final observation for a time-limit truncation to bootstrap from); set "
        "handle_timeout_termination: false");
  if (optimize_memory_usage && slots_ < 2)
    throw std::invalid_argument(
        "optimize_memory_usage needs buffer_size of at least two transitions per env");
  const int64_t columns = slots_ * n_envs_;
  obs_ = ObservationColumns(observation_space, columns);
  next_obs_ = ObservationColumns(observation_space, optimize_memory_usage ? 0 : columns);
  actions_.resize(act_dim, columns);
  rewards_.resize(columns);
  dones_.resize(columns);
}

ReplayBuffer::ReplayBuffer(int64_t buffer_size, int n_envs, int obs_dim, int act_dim,
                           bool handle_timeout_termination)
    : ReplayBuffer(buffer_size, n_envs,
                   Space::box(-std::numeric_limits<float>::infinity(),
                              std::numeric_limits<float>::infinity(), {obs_dim}),
                   act_dim, handle_timeout_termination) {}

void ReplayBuffer::add(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                       const Eigen::Ref<const Eigen::MatrixXf>& buffer_actions, const VecEnv& env) {
  for (int e = 0; e < n_envs_; ++e) {
    const int64_t k = pos_ * n_envs_ + e;
    obs_.set(k, obs.col(e).data());
    // SB3 _store_transition: the next observation of a finished episode is its final one;
    // under VecNormalize the original observations and rewards are stored (batches are
    // normalised when sampled, with the statistics of that time).
    const float* next =
        env.done(e) ? env.original_final_obs().col(e).data() : env.original_obs().col(e).data();
    if (optimize_memory_usage_)
      obs_.set(following(k), next);  // SB3: observations[(pos + 1) % buffer_size] = next_obs
    else
      next_obs_.set(k, next);
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

void ReplayBuffer::copy_transition(int64_t k, int j, ReplayBatch& batch) const {
  obs_.get(k, batch.obs.col(j).data());
  if (optimize_memory_usage_)
    obs_.get(following(k), batch.next_obs.col(j).data());
  else
    next_obs_.get(k, batch.next_obs.col(j).data());
  batch.actions.col(j) = actions_.col(k);
  batch.rewards(j) = rewards_(k);
  batch.dones(j) = dones_(k);
}

void ReplayBuffer::sample(int batch_size, Rng& rng, ReplayBatch& batch) const {
  const int64_t upper = full_ ? slots_ : pos_;
  if (upper == 0) throw std::logic_error("ReplayBuffer::sample on an empty buffer");
  size_batch(batch_size, batch);
  for (int j = 0; j < batch_size; ++j) {
    // SB3: batch_inds = randint(0, upper_bound); env_indices = randint(0, n_envs). With
    // optimize_memory_usage and a full buffer, (randint(1, buffer_size) + pos) % buffer_size:
    // every slot but the one being written, whose next observation is not there yet.
    const int64_t slot =
        optimize_memory_usage_ && full_
            ? (1 + static_cast<int64_t>(rng.below(static_cast<uint64_t>(slots_ - 1))) + pos_) %
                  slots_
            : static_cast<int64_t>(rng.below(static_cast<uint64_t>(upper)));
    const int64_t env = n_envs_ > 1 ? static_cast<int64_t>(rng.below(n_envs_)) : 0;
    copy_transition(slot * n_envs_ + env, j, batch);
  }
}

int64_t ReplayBuffer::stored_observations() const {
  // With optimize_memory_usage the slot after the last transition holds its next observation
  // (none before the first: an empty buffer stores nothing, as the checkpoint budget expects).
  if (full_) return capacity();
  if (pos_ == 0) return 0;
  return std::min(pos_ + (optimize_memory_usage_ ? 1 : 0), slots_) * n_envs_;
}

void ReplayBuffer::write_state(StateWriter out) const {
  // Only the filled columns: a checkpoint early in a 1e6-transition run stays small.
  const int64_t used = size();
  obs_.write_state(out, "obs", stored_observations());
  if (!optimize_memory_usage_) next_obs_.write_state(out, "next_obs", used);
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
  obs_.read_state(in, "obs", stored_observations());
  if (!optimize_memory_usage_) next_obs_.read_state(in, "next_obs", used);
  get_matrix(in, "actions", actions_.leftCols(used));
  Eigen::VectorXf column(used);
  get_matrix(in, "rewards", column);
  rewards_.head(used) = column.transpose();
  get_matrix(in, "dones", column);
  dones_.head(used) = column.transpose();
}

}  // namespace rlrun
