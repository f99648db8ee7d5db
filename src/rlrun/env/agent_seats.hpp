#pragma once
// One policy per agent (independent learners): each agent of a multi-agent env
// (include/rlrun/env.hpp, num_agents() > 1) trained by a learner of its own, with its own
// networks, optimiser and run directory, as RLlib's policy-per-agent mapping or k SB3 models
// over one PettingZoo parallel env do. runtime/run/per_agent_training.hpp runs the k learners,
// each on a thread of its own; this file is what lets each of them see an ordinary
// single-agent env.
//
// A seat (AgentSeat) is agent a's view of one shared multi-agent env: reset() and step() of
// the seat hand in agent a's part and wait until every agent's seat has done the same; the
// last seat to arrive resets or steps the shared env once (step_agents with every agent's
// action), and each seat then returns its own agent's observation, reward and flags. The
// learners thus meet once per env step, whatever their algorithm does between steps — they
// run the same experiment, so they step, reset and evaluate in the same order.
//
// Which shared env a seat belongs to: the k learners build their envs in the same order (the
// training VecEnv's copies, then the evaluation env, ...), so the m-th seat a learner asks
// for belongs to the m-th shared env (SeatTable::claim), built by the first learner to ask.
//
// When a learner stops (finished, failed, interrupted), it leaves the table: any seat that
// then waits for it, or arrives later, throws TrainingStopped naming the agent and why, so no
// learner waits forever for one that is gone.
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/env.hpp"

namespace rlrun {

// A seat's learner cannot go on because another agent's learner stopped, or because the shared
// env failed (the message says which).
class SeatsStopped : public RuntimeFailure {
 public:
  using RuntimeFailure::RuntimeFailure;
};

class SharedMultiAgentEnv;

class SeatTable {
 public:
  // `agent_names` in the env's agent order (env/agent_names.hpp), for the messages.
  explicit SeatTable(std::vector<std::string> agent_names);

  int agents() const { return static_cast<int>(names_.size()); }
  const std::string& agent_name(int agent) const { return names_[agent]; }

  // The shared env of agent `agent`'s next seat: the one its m-th call gets is the one every
  // other agent's m-th call gets; `build` makes it when no agent asked for it before. The env
  // must have agents() agents.
  std::shared_ptr<SharedMultiAgentEnv> claim(int agent, const std::function<EnvPtr()>& build);

  // Agent `agent`'s learner stopped: `why` ("finished", or the error). Wakes every waiting
  // seat; from now on a seat that needs this agent throws SeatsStopped.
  void leave(int agent, const std::string& why);

 private:
  friend class SharedMultiAgentEnv;
  std::vector<std::string> names_;
  std::mutex mutex_;  // guards everything below and every shared env's rendezvous
  // Signalled when any shared env's round is done or a learner leaves: a seat waits at one
  // shared env at a time, so k learners are at most k - 1 waiters (each checks its own round).
  std::condition_variable changed_;
  // Shared env m until every agent has claimed it (then null: its seats keep it alive).
  std::vector<std::shared_ptr<SharedMultiAgentEnv>> envs_;
  std::vector<int> claims_;      // per shared env: how many agents have claimed it
  std::vector<size_t> claimed_;  // per agent: how many shared envs it has claimed
  std::string stopped_;          // "" or why a learner left: the message seats throw
};

// One multi-agent env shared by its agents' seats, and the rendezvous that steps it.
class SharedMultiAgentEnv {
 public:
  SharedMultiAgentEnv(SeatTable& table, EnvPtr env);
  SharedMultiAgentEnv(const SharedMultiAgentEnv&) = delete;
  SharedMultiAgentEnv& operator=(const SharedMultiAgentEnv&) = delete;

  Env& env() { return *env_; }
  const Env& env() const { return *env_; }

  // Agent `agent`'s part of a reset (its seed: agent 0's is the one used, as every learner
  // seeds its envs from the run's seed) and of a step; returns when the env has done it, with
  // the agent's observation in `obs`.
  void reset(int agent, std::optional<uint64_t> seed, std::span<float> obs);
  StepResult step(int agent, std::span<const float> action, std::span<float> obs);

 private:
  friend class SeatTable;
  enum class Op { kNone, kReset, kStep };
  // Waits for every seat to hand in `op` for this round; the last one runs it. Called with the
  // table's lock held (`lock`).
  void meet(std::unique_lock<std::mutex>& lock, int agent, Op op);
  void run_round(Op op);

  SeatTable& table_;
  EnvPtr env_;
  const int obs_dim_;
  const int act_dim_;
  Op op_ = Op::kNone;
  int arrived_ = 0;
  uint64_t round_ = 0;
  std::optional<uint64_t> seed_;
  std::vector<float> actions_;  // agent-major
  std::vector<float> obs_;      // agent-major
  std::vector<StepResult> results_;
  std::optional<uint64_t> failed_round_;  // the round in which the env threw ...
  // ... what it threw: every seat of that round rethrows it, keeping its type (an Interrupted
  // from a simulator's start stops every learner as it stops a single run).
  std::exception_ptr failure_;
};

// Agent `agent`'s seat at a shared env: an ordinary single-agent Env for its learner. Its Info
// is the shared env's, with the agent's own action mask (env/action_mask.hpp) under
// action_mask.0 ... and the other agents' left out. It cannot save its state (the learners
// would have to snapshot the shared env together), so a per-agent run's checkpoints hold the
// models only.
class AgentSeat final : public Env {
 public:
  AgentSeat(std::shared_ptr<SharedMultiAgentEnv> shared, int agent);

  const Space& observation_space() const override { return shared_->env().observation_space(); }
  const Space& action_space() const override { return shared_->env().action_space(); }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  const Info& info() const override { return info_; }
  std::string id() const override { return shared_->env().id(); }
  RenderSpec render_spec() const override { return shared_->env().render_spec(); }
  bool render(Frame& frame) const override { return shared_->env().render(frame); }

 private:
  void copy_info();

  std::shared_ptr<SharedMultiAgentEnv> shared_;
  const int agent_;
  const int mask_size_;
  Info info_;
  std::vector<int> info_from_;  // info_ key i <- the shared env's key info_from_[i]
  size_t shared_keys_seen_ = 0;
};

}  // namespace rlrun
