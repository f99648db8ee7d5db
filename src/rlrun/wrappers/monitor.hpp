#pragma once
// SB3's Monitor wrapper (stable_baselines3/common/monitor.py): records each episode's return,
// length and time, writes them to `<rank>.monitor.csv` in SB3's exact format so that
// `stable_baselines3.common.monitor.load_results` reads it:
//     #{"t_start": 1732243200.123456, "env_id": "CartPole-v1"}
//     r,l,t
//     21.0,21,0.000153
// and reports a finished episode through info keys `episode.r`, `episode.l`, `episode.t` (SB3's
// info["episode"]), which the algorithms read for rollout/ep_rew_mean. Each of `info_keywords`
// (SB3's Monitor argument; runtime/experiment/env_factory.hpp picks them) becomes a column after r,l,t
// and an info key `episode.<key>` with its value at the episode's last step, which training
// averages into rollout/<key> (algos/common/episode_stats.hpp). A multi-agent env's row ends
// with each agent's own return (r_0, r_1, ...); `r` is their sum.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/float_format.hpp"
#include "rlrun/env/split_step.hpp"
#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class Monitor : public Wrapper, public SplitStep {
 public:
  // Observations and actions pass unchanged (rlrun export).
  bool exports_unchanged() const override { return true; }
  // `path` empty: no file, statistics only. `t_start` is Unix time in seconds. `append`
  // continues an existing file of a resumed run (no new header).
  Monitor(EnvPtr inner, const std::string& path, double t_start,
          std::vector<std::string> info_keywords = {}, bool append = false);
  ~Monitor() override;
  Monitor(const Monitor&) = delete;
  Monitor& operator=(const Monitor&) = delete;

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  // The two halves of step() (env/split_step.hpp), forwarded to the inner env.
  bool steps_asynchronously() const override;
  void start_step(std::span<const float> action) override;
  StepResult finish_step(std::span<float> obs) override;
  void step_agents(std::span<const float> actions, std::span<float> obs,
                   std::span<StepResult> results) override;
  bool splits_agents() const override { return asynchronous_steps(*inner_) != nullptr; }
  void start_step_agents(std::span<const float> actions) override;
  void finish_step_agents(std::span<float> obs, std::span<StepResult> results) override;
  const Info& info() const override { return info_; }

  int total_episodes() const { return total_episodes_; }
  // The running episode's return so far (the reward as the inner env gives it).
  double episode_return() const { return episode_return_; }
  int64_t total_steps() const { return total_steps_; }

 protected:
  // Resume: the running episode's return and length, the totals, and t_start (so that the
  // `t` column keeps counting wall time from the original start).
  void write_own_state(StateWriter& out) const override;
  void read_own_state(const StateReader& in) override;

 private:
  void require_not_ended() const;
  // Counts one step of `reward`; writes the episode's row when it ended.
  void account(double reward, bool episode_ended);
  // The same for a step of every agent.
  void account_agents(std::span<const StepResult> results);
  void copy_inner_info();
  int agent_columns() const { return num_agents() > 1 ? num_agents() : 0; }
  CheckedFile file_;  // every row flushed and checked (core/checked_file.hpp)
  double t_start_;
  std::chrono::steady_clock::time_point clock_start_;
  Info info_;
  std::vector<int> inner_to_own_;         // inner info index -> own index
  std::vector<std::string> keywords_;     // info_keywords: monitor.csv columns after r,l,t
  std::vector<int> keyword_inner_index_;  // their inner info index (-1: not declared yet)
  std::vector<int> keyword_own_index_;    // their `episode.<key>` index in info_
  int episode_r_ = -1, episode_l_ = -1, episode_t_ = -1;
  double episode_return_ = 0.0;
  std::vector<double> agent_returns_;  // several agents: each one's return this episode
  int64_t episode_length_ = 0;
  int total_episodes_ = 0;
  int64_t total_steps_ = 0;
  bool needs_reset_ = true;
};

}  // namespace rlrun
