#include "rlrun/env/agent_seats.hpp"

#include <algorithm>
#include <charconv>
#include <string_view>
#include <utility>

#include "rlrun/env/action_mask.hpp"

namespace rlrun {

SeatTable::SeatTable(std::vector<std::string> agent_names)
    : names_(std::move(agent_names)), claimed_(names_.size(), 0) {}

std::shared_ptr<SharedMultiAgentEnv> SeatTable::claim(int agent,
                                                      const std::function<EnvPtr()>& build) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!stopped_.empty()) throw SeatsStopped(stopped_);
  const size_t index = claimed_[agent]++;
  if (index == envs_.size()) {
    // The first learner to ask builds it, holding the others back until it exists: building
    // starts no simulator (SUMO starts at the first reset) beyond a Python worker at most.
    EnvPtr env = build();
    if (env->num_agents() != agents())
      throw RuntimeFailure(env->id() + " has " + std::to_string(env->num_agents()) +
                           " agents where the learners expected " + std::to_string(agents()));
    envs_.push_back(std::make_shared<SharedMultiAgentEnv>(*this, std::move(env)));
    claims_.push_back(0);
  }
  std::shared_ptr<SharedMultiAgentEnv> shared = envs_[index];
  // Once every agent has its seat the table lets go, so the env lives as long as its seats.
  if (++claims_[index] == agents()) envs_[index].reset();
  return shared;
}

void SeatTable::leave(int agent, const std::string& why) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (stopped_.empty())
    stopped_ = "agent " + names_[agent] + "'s learner stopped (" + why +
               "), so the other agents' learners cannot step their shared env";
  changed_.notify_all();
}

SharedMultiAgentEnv::SharedMultiAgentEnv(SeatTable& table, EnvPtr env)
    : table_(table),
      env_(std::move(env)),
      obs_dim_(env_->observation_space().flat_dim()),
      act_dim_(env_->action_space().flat_dim()),
      actions_(static_cast<size_t>(act_dim_) * table.agents(), 0.0f),
      obs_(static_cast<size_t>(obs_dim_) * table.agents(), 0.0f),
      results_(static_cast<size_t>(table.agents())) {}

void SharedMultiAgentEnv::run_round(Op op) {
  try {
    if (op == Op::kReset) {
      env_->reset(seed_, obs_);
      std::fill(results_.begin(), results_.end(), StepResult{});
    } else {
      env_->step_agents(actions_, obs_, results_);
    }
  } catch (...) {
    failed_round_ = round_;
    failure_ = std::current_exception();
  }
}

void SharedMultiAgentEnv::meet(std::unique_lock<std::mutex>& lock, int agent, Op op) {
  if (!table_.stopped_.empty()) throw SeatsStopped(table_.stopped_);
  if (op_ != Op::kNone && op_ != op)
    throw SeatsStopped("the learners are out of step at " + env_->id() + ": agent " +
                       table_.agent_name(agent) + " asked to " +
                       (op == Op::kReset ? "reset" : "step") + " while the others " +
                       (op_ == Op::kReset ? "reset" : "stepped"));
  op_ = op;
  const uint64_t round = round_;
  if (++arrived_ == table_.agents()) {
    run_round(op);
    arrived_ = 0;
    op_ = Op::kNone;
    ++round_;
    table_.changed_.notify_all();
  } else {
    table_.changed_.wait(lock, [&] { return round_ != round || !table_.stopped_.empty(); });
    if (round_ == round) throw SeatsStopped(table_.stopped_);
  }
  if (failed_round_ == round) std::rethrow_exception(failure_);
}

void SharedMultiAgentEnv::reset(int agent, std::optional<uint64_t> seed, std::span<float> obs) {
  std::unique_lock<std::mutex> lock(table_.mutex_);
  if (agent == 0) seed_ = seed;
  meet(lock, agent, Op::kReset);
  std::copy_n(obs_.begin() + static_cast<ptrdiff_t>(agent) * obs_dim_, obs_dim_, obs.begin());
}

StepResult SharedMultiAgentEnv::step(int agent, std::span<const float> action,
                                     std::span<float> obs) {
  std::unique_lock<std::mutex> lock(table_.mutex_);
  std::copy_n(action.begin(), act_dim_,
              actions_.begin() + static_cast<ptrdiff_t>(agent) * act_dim_);
  meet(lock, agent, Op::kStep);
  std::copy_n(obs_.begin() + static_cast<ptrdiff_t>(agent) * obs_dim_, obs_dim_, obs.begin());
  return results_[agent];
}

AgentSeat::AgentSeat(std::shared_ptr<SharedMultiAgentEnv> shared, int agent)
    : shared_(std::move(shared)),
      agent_(agent),
      mask_size_(action_mask_size(shared_->env().action_space())) {
  copy_info();
}

void AgentSeat::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  shared_->reset(agent_, seed, obs);
  copy_info();
}

StepResult AgentSeat::step(std::span<const float> action, std::span<float> obs) {
  const StepResult result = shared_->step(agent_, action, obs);
  copy_info();
  return result;
}

// The shared env's Info is read between rounds, when no seat can be changing it: the next
// round needs this seat too.
void AgentSeat::copy_info() {
  const Info& shared = shared_->env().info();
  const std::vector<std::string>& keys = shared.keys();
  // Keys are declared as the env meets them (a Python env's on its first reply): map new ones.
  for (size_t k = shared_keys_seen_; k < keys.size(); ++k) {
    constexpr std::string_view kMask = "action_mask.";
    const std::string& key = keys[k];
    if (mask_size_ > 0 && key.rfind(kMask, 0) == 0) {
      // Agent a's mask entries are action_mask.<a * size + j> (env/action_mask.hpp): this
      // seat's agent reads them as its own action_mask.<j>; the other agents' are not its.
      int entry = -1;
      const char* first = key.data() + kMask.size();
      std::from_chars(first, key.data() + key.size(), entry);
      const int own = entry - agent_ * mask_size_;
      if (own < 0 || own >= mask_size_) continue;
      info_from_.resize(static_cast<size_t>(info_.add_key(action_mask_key(own))) + 1, -1);
      info_from_[info_.find(action_mask_key(own))] = static_cast<int>(k);
      continue;
    }
    info_from_.resize(static_cast<size_t>(info_.add_key(key)) + 1, -1);
    info_from_[info_.find(key)] = static_cast<int>(k);
  }
  shared_keys_seen_ = keys.size();
  for (size_t i = 0; i < info_from_.size(); ++i)
    info_.set(static_cast<int>(i), info_from_[i] < 0 ? Info::kAbsent : shared.get(info_from_[i]));
}

}  // namespace rlrun
