#pragma once
// SB3's HerReplayBuffer (stable_baselines3/her/her_replay_buffer.py, SB3 2.x; paper: Andrychowicz
// et al. 2017, arXiv:1707.01495) on rlrun's ReplayBuffer: transitions of a goal-conditioned env
// (env/goal_env.hpp) are stored as they happened, and relabelled at sample time.
//
//   * Each stored transition knows its episode (ep_start, ep_length per slot and env, set when
//     the episode ends); transitions of an unfinished episode, or of an episode partly
//     overwritten by the circular buffer, are not sampled.
//   * sample(): batch_size transitions uniform over the valid ones (with replacement); the
//     first int(her_ratio * batch_size) are virtual, her_ratio = 1 - 1 / (n_sampled_goal + 1):
//     their desired goal (in obs and next_obs) is replaced by the achieved goal of next_obs of
//     a transition of the same episode — `final`: the last; `future`: uniform from the
//     transition itself to the last (SB3's inclusive variant); `episode`: uniform over the
//     episode — and their reward recomputed by the env's compute_reward(next achieved goal,
//     new goal). The rest are real transitions as stored.
//   * Timeouts as the ReplayBuffer's (handle_timeout_termination): a truncated transition
//     bootstraps.
// The flat observation is the Dict's keys in sorted order (achieved_goal, desired_goal,
// observation): the goals are slices of it. The info dict is not passed to compute_reward
// (SB3's default, copy_info_dict=False).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/algos/common/replay_buffer.hpp"
#include "rlrun/env/goal_env.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

enum class GoalSelection { kFuture, kFinal, kEpisode };
// "future", "final" or "episode" (SB3's KEY_TO_GOAL_STRATEGY); throws std::invalid_argument.
GoalSelection parse_goal_selection(const std::string& name);

class HerReplayBuffer : public ReplayBuffer {
 public:
  // `observation_space`: a Dict with achieved_goal, desired_goal (same shape) and observation;
  // `rewards_of`: the env's compute_reward (the first env's, as SB3's env_method(indices=[0])),
  // alive as long as the buffer says so, or nullptr until set_goal_env (a buffer restored from a
  // checkpoint before the env exists). Throws std::invalid_argument otherwise.
  HerReplayBuffer(int64_t buffer_size, int n_envs, const Space& observation_space, int act_dim,
                  const GoalEnv* rewards_of, int n_sampled_goal, GoalSelection selection,
                  bool handle_timeout_termination = true);

  // The env whose compute_reward relabels (SB3 sets HerReplayBuffer.env in learn / set_env).
  void set_goal_env(const GoalEnv* rewards_of) { rewards_of_ = rewards_of; }

  void add(const Eigen::Ref<const Eigen::MatrixXf>& obs,
           const Eigen::Ref<const Eigen::MatrixXf>& buffer_actions, const VecEnv& env) override;
  // Throws std::logic_error before the first episode has ended (SB3: "Unable to sample before
  // the end of the first episode") or without a goal env.
  void sample(int batch_size, Rng& rng, ReplayBatch& batch) const override;

  double her_ratio() const { return her_ratio_; }
  // Finished transitions that can be sampled.
  int64_t valid_transitions() const { return valid_; }

  void write_state(StateWriter out) const override;
  // Refuses (StateMismatch, naming the env and slot) bookkeeping add() could not have written:
  // every index and length is checked against pos, full and the others.
  void read_state(const StateReader& in) override;

 private:
  // SB3 _compute_episode_length: the episode env `e` just finished spans
  // [current_ep_start, pos).
  void close_episode(int e);
  // "" when env `e`'s episode bookkeeping (ep_start_, ep_length_, current_ep_start_) is what
  // add() can have written at this pos_ and full_, else why not (read_state).
  std::string describe_inconsistent_episodes(int e) const;

  const GoalEnv* rewards_of_;
  GoalSelection selection_;
  double her_ratio_;
  int achieved_offset_ = 0, desired_offset_ = 0, goal_dim_ = 0;
  // Per column (slot * n_envs + env), as SB3's (buffer_size, n_envs) arrays.
  std::vector<int64_t> ep_start_, ep_length_;
  std::vector<int64_t> current_ep_start_;  // per env
  int64_t valid_ = 0;                      // entries of ep_length_ > 0, kept as they change
  // sample() scratch: the virtual transitions' next achieved goals and new goals.
  mutable Eigen::MatrixXf achieved_scratch_, goal_scratch_;
  mutable Eigen::RowVectorXf reward_scratch_;
};

}  // namespace rlrun
