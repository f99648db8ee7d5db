#include "rlrun/algos/common/her_replay_buffer.hpp"

#include <algorithm>
#include <stdexcept>

#include "rlrun/core/state_dict.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

GoalSelection parse_goal_selection(const std::string& name) {
  if (name == "future") return GoalSelection::kFuture;
  if (name == "final") return GoalSelection::kFinal;
  if (name == "episode") return GoalSelection::kEpisode;
  throw std::invalid_argument("goal_selection_strategy: unknown '" + name +
                              "' (future, final or episode)");
}

namespace {

int key_index(const Space& space, const std::string& key) {
  const auto& keys = space.keys();
  const auto it = std::find(keys.begin(), keys.end(), key);
  if (it == keys.end())
    throw std::invalid_argument("HerReplayBuffer needs a Dict observation with '" + key +
                                "' (a goal-conditioned env: observation, achieved_goal, "
                                "desired_goal); this one is " +
                                space.describe());
  return static_cast<int>(it - keys.begin());
}

}  // namespace

HerReplayBuffer::HerReplayBuffer(int64_t buffer_size, int n_envs, const Space& observation_space,
                                 int act_dim, const GoalEnv* rewards_of, int n_sampled_goal,
                                 GoalSelection selection, bool handle_timeout_termination)
    : ReplayBuffer(buffer_size, n_envs, observation_space, act_dim, handle_timeout_termination),
      rewards_of_(rewards_of),
      selection_(selection),
      her_ratio_(1.0 - 1.0 / (n_sampled_goal + 1.0)) {
  if (!observation_space.is_dict())
    throw std::invalid_argument(
        "HerReplayBuffer needs a Dict observation (observation, "
        "achieved_goal, desired_goal); this one is " +
        observation_space.describe());
  if (n_sampled_goal < 0) throw std::invalid_argument("n_sampled_goal must be >= 0");
  key_index(observation_space, "observation");
  const int achieved = key_index(observation_space, "achieved_goal");
  const int desired = key_index(observation_space, "desired_goal");
  goal_dim_ = observation_space.subspaces()[achieved].flat_dim();
  if (observation_space.subspaces()[desired].flat_dim() != goal_dim_)
    throw std::invalid_argument("HerReplayBuffer: achieved_goal and desired_goal differ in size");
  achieved_offset_ = observation_space.offset(static_cast<size_t>(achieved));
  desired_offset_ = observation_space.offset(static_cast<size_t>(desired));
  ep_start_.assign(static_cast<size_t>(capacity()), 0);
  ep_length_.assign(static_cast<size_t>(capacity()), 0);
  current_ep_start_.assign(static_cast<size_t>(n_envs_), 0);
}

void HerReplayBuffer::add(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                          const Eigen::Ref<const Eigen::MatrixXf>& buffer_actions,
                          const VecEnv& env) {
  // Overwriting the first transition of an old episode: the rest of it can no longer be
  // sampled either (SB3 sets its length to 0 from here to its end).
  for (int e = 0; e < n_envs_; ++e) {
    const size_t k = static_cast<size_t>(pos_ * n_envs_ + e);
    const int64_t length = ep_length_[k];
    if (length > 0) {
      const int64_t end = ep_start_[k] + length;
      for (int64_t slot = pos_; slot < end; ++slot) {
        int64_t& old_length = ep_length_[static_cast<size_t>((slot % slots_) * n_envs_ + e)];
        valid_ -= old_length > 0;
        old_length = 0;
      }
    }
    ep_start_[k] = current_ep_start_[static_cast<size_t>(e)];
  }
  ReplayBuffer::add(obs, buffer_actions, env);
  for (int e = 0; e < n_envs_; ++e)
    if (env.done(e)) close_episode(e);
}

void HerReplayBuffer::close_episode(int e) {
  const int64_t start = current_ep_start_[static_cast<size_t>(e)];
  int64_t end = pos_;
  if (end <= start) end += slots_;  // the episode wrapped around the buffer's end
  for (int64_t slot = start; slot < end; ++slot)
    ep_length_[static_cast<size_t>((slot % slots_) * n_envs_ + e)] = end - start;
  valid_ += end - start;  // the episode's slots were not valid before (its own, still open)
  current_ep_start_[static_cast<size_t>(e)] = pos_;
}

void HerReplayBuffer::sample(int batch_size, Rng& rng, ReplayBatch& batch) const {
  const int64_t filled = size();
  if (filled == 0 || valid_ == 0)
    throw std::logic_error(
        "HerReplayBuffer: no finished episode to sample from yet; choose learning_starts "
        "greater than the longest episode (SB3 says the same)");
  if (!rewards_of_)
    throw std::logic_error("HerReplayBuffer: no goal env to recompute rewards with");
  size_batch(batch_size, batch);
  const int n_virtual = static_cast<int>(her_ratio_ * batch_size);
  achieved_scratch_.resize(goal_dim_, n_virtual);
  goal_scratch_.resize(goal_dim_, n_virtual);
  reward_scratch_.resize(n_virtual);
  for (int j = 0; j < batch_size; ++j) {
    // Uniform over the valid transitions (SB3: np.random.choice(valid_indices)): draw among
    // the filled columns until one belongs to a finished, intact episode.
    int64_t k = 0;
    do {
      k = static_cast<int64_t>(rng.below(static_cast<uint64_t>(filled)));
    } while (ep_length_[static_cast<size_t>(k)] == 0);
    copy_transition(k, j, batch);
    if (j >= n_virtual) continue;
    // A virtual transition: a new desired goal from the same episode (SB3 _sample_goals).
    const int64_t slot = k / n_envs_, e = k % n_envs_;
    const int64_t start = ep_start_[static_cast<size_t>(k)],
                  length = ep_length_[static_cast<size_t>(k)];
    int64_t index = 0;  // within the episode
    switch (selection_) {
      case GoalSelection::kFinal: index = length - 1; break;
      case GoalSelection::kFuture: {
        const int64_t current = ((slot - start) % slots_ + slots_) % slots_;
        index = current + static_cast<int64_t>(rng.below(static_cast<uint64_t>(length - current)));
        break;
      }
      case GoalSelection::kEpisode:
        index = static_cast<int64_t>(rng.below(static_cast<uint64_t>(length)));
        break;
    }
    const int64_t goal_column = ((start + index) % slots_) * n_envs_ + e;
    next_obs_.get(goal_column, achieved_offset_, goal_dim_, goal_scratch_.col(j).data());
    const auto new_goal = goal_scratch_.col(j);
    batch.obs.col(j).segment(desired_offset_, goal_dim_) = new_goal;
    batch.next_obs.col(j).segment(desired_offset_, goal_dim_) = new_goal;
    // r_t = reward(next achieved goal, desired goal): s_{t+1} holds what a_t achieved.
    achieved_scratch_.col(j) = batch.next_obs.col(j).segment(achieved_offset_, goal_dim_);
  }
  if (n_virtual > 0) {
    rewards_of_->compute_reward(achieved_scratch_, goal_scratch_, reward_scratch_);
    batch.rewards.head(n_virtual) = reward_scratch_;
  }
}

void HerReplayBuffer::write_state(StateWriter out) const {
  ReplayBuffer::write_state(out);
  out.put_vector("her/ep_start", ep_start_);
  out.put_vector("her/ep_length", ep_length_);
  out.put_vector("her/current_ep_start", current_ep_start_);
}

void HerReplayBuffer::read_state(const StateReader& in) {
  ReplayBuffer::read_state(in);
  ep_start_ = in.get_span<int64_t>("her/ep_start", capacity());
  ep_length_ = in.get_span<int64_t>("her/ep_length", capacity());
  current_ep_start_ = in.get_span<int64_t>("her/current_ep_start", n_envs_);
  // A checkpoint is untrusted: its indices must agree with each other (issue 41: an unfinished
  // episode "starting" beyond the written slots relabelled goals from uninitialised memory).
  for (int e = 0; e < n_envs_; ++e) {
    const std::string problem = describe_inconsistent_episodes(e);
    if (!problem.empty())
      throw StateMismatch("checkpoint HER buffer: env " + std::to_string(e) + ": " + problem);
  }
  valid_ = std::count_if(ep_length_.begin(), ep_length_.end(), [](int64_t l) { return l > 0; });
}

namespace {

std::string slot_record(int64_t slot, int64_t start, int64_t length) {
  return "slot " + std::to_string(slot) + " records an episode of " + std::to_string(length) +
         " from slot " + std::to_string(start);
}

}  // namespace

// What add() and close_episode() leave, restated as checks: the unfinished episode runs from
// current_ep_start to pos with no length yet; each finished episode lies inside the written
// slots and every one of its slots records the same start and length; when the buffer is full,
// the write position is at the start of the oldest episode (add() invalidates an episode from
// there on), never inside one.
std::string HerReplayBuffer::describe_inconsistent_episodes(int e) const {
  const auto column = [&](int64_t slot) { return static_cast<size_t>(slot * n_envs_ + e); };
  const auto start = [&](int64_t slot) { return ep_start_[column(slot)]; };
  const auto length = [&](int64_t slot) { return ep_length_[column(slot)]; };
  const int64_t written = full_ ? slots_ : pos_;
  const int64_t open = current_ep_start_[static_cast<size_t>(e)];
  if (open < 0 || open >= slots_ || (!full_ && open > pos_))
    return "the unfinished episode starts at slot " + std::to_string(open) + ", but " +
           std::to_string(written) + " of " + std::to_string(slots_) + " slots are written";
  for (int64_t slot = open; slot != pos_; slot = (slot + 1) % slots_)
    if (length(slot) != 0 || start(slot) != open)
      return "slot " + std::to_string(slot) + " of the unfinished episode from slot " +
             std::to_string(open) + " is recorded as another episode";
  if (full_ && length(pos_) != 0 && start(pos_) != pos_)
    return slot_record(pos_, start(pos_), length(pos_)) + ", but the write position is inside it";
  std::vector<bool> checked(static_cast<size_t>(slots_), false);  // each episode once: linear
  for (int64_t slot = 0; slot < slots_; ++slot) {
    const int64_t first = start(slot), n = length(slot);
    if (n == 0 || checked[static_cast<size_t>(slot)]) continue;
    if (n < 0 || n > written || first < 0 || first >= slots_ || (!full_ && first + n > written))
      return slot_record(slot, first, n) + ", outside the " + std::to_string(written) +
             " written slots";
    if ((slot - first + slots_) % slots_ >= n)
      return slot_record(slot, first, n) + " that does not cover it";
    for (int64_t i = 0; i < n; ++i) {
      const int64_t other = (first + i) % slots_;
      if (start(other) != first || length(other) != n)
        return slot_record(slot, first, n) + ", but its slot " + std::to_string(other) +
               " records another";
      checked[static_cast<size_t>(other)] = true;
    }
  }
  return "";
}

}  // namespace rlrun
