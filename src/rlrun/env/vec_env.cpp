#include "rlrun/env/vec_env.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/state_dict.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

namespace rlrun {

VecEnv::VecEnv(std::vector<EnvPtr> envs) : envs_(std::move(envs)) {
  if (envs_.empty()) throw std::invalid_argument("VecEnv: needs at least one env");
  for (size_t i = 0; i < envs_.size(); ++i) {
    if (!envs_[i]) throw std::invalid_argument("VecEnv: env " + std::to_string(i) + " is null");
    // SB3 builds every env from one factory; differing spaces mean a wrong env list.
    if (!(envs_[i]->observation_space() == envs_[0]->observation_space()))
      throw std::invalid_argument("VecEnv: env " + std::to_string(i) + " has observation space " +
                                  envs_[i]->observation_space().describe() + " but env 0 has " +
                                  envs_[0]->observation_space().describe());
    if (!(envs_[i]->action_space() == envs_[0]->action_space()))
      throw std::invalid_argument("VecEnv: env " + std::to_string(i) + " has action space " +
                                  envs_[i]->action_space().describe() + " but env 0 has " +
                                  envs_[0]->action_space().describe());
  }
  size_t most_agents = 1;
  for (size_t c = 0; c < envs_.size(); ++c) {
    const int agents = envs_[c]->num_agents();
    if (agents < 1)
      throw std::invalid_argument("VecEnv: env " + std::to_string(c) + " has no agents");
    first_slot_.push_back(static_cast<int>(slot_env_.size()));
    agents_.push_back(agents);
    slot_env_.insert(slot_env_.end(), static_cast<size_t>(agents), static_cast<int>(c));
    most_agents = std::max(most_agents, static_cast<size_t>(agents));
  }
  const int n = num_envs();
  obs_dim_ = observation_space().flat_dim();
  act_dim_ = action_space().flat_dim();
  seeds_.assign(envs_.size(), std::nullopt);
  obs_.setZero(obs_dim_, n);
  final_obs_.setConstant(obs_dim_, n, std::numeric_limits<float>::quiet_NaN());
  rewards_.setZero(n);
  terminated_.assign(n, 0);
  truncated_.assign(n, 0);
  agent_results_.resize(most_agents);
  infos_.resize(envs_.size());
  for (int c = 0; c < num_copies(); ++c) copy_info(c);
  for (EnvPtr& env : envs_) split_.push_back(asynchronous_steps(*env));
  if (std::find(split_.begin(), split_.end(), nullptr) != split_.end()) split_.clear();
}

VecEnv::VecEnv(VecEnv&&) noexcept = default;
VecEnv& VecEnv::operator=(VecEnv&&) noexcept = default;
VecEnv::~VecEnv() = default;

void VecEnv::seed(uint64_t seed) {
  for (int c = 0; c < num_copies(); ++c) seeds_[c] = seed + static_cast<uint64_t>(c);
}

const Eigen::MatrixXf& VecEnv::reset() {
  for (int c = 0; c < num_copies(); ++c) reset_copy(c);
  std::fill(terminated_.begin(), terminated_.end(), 0);
  std::fill(truncated_.begin(), truncated_.end(), 0);
  rewards_.setZero();
  // SB3 _reset_seeds: a seed applies to one reset only.
  seeds_.assign(seeds_.size(), std::nullopt);
  final_obs_.setConstant(std::numeric_limits<float>::quiet_NaN());
  if (hook_) {
    original_obs_ = obs_;
    original_final_obs_ = final_obs_;
    original_rewards_ = rewards_;
    hook_->after_reset(obs_);
  }
  return obs_;
}

void VecEnv::set_step_hook(std::unique_ptr<VecStepHook> hook) {
  if (hook && num_envs() != num_copies())
    throw std::invalid_argument("VecEnv: a step hook needs single-agent envs");
  hook_ = std::move(hook);
  done_.assign(static_cast<size_t>(num_envs()), 0);
}

void VecEnv::run_step_hook() {
  for (size_t i = 0; i < done_.size(); ++i) done_[i] = terminated_[i] || truncated_[i];
  // SB3 VecNormalize keeps old_obs / old_reward: the values as the envs gave them.
  original_obs_ = obs_;
  original_final_obs_ = final_obs_;
  original_rewards_ = rewards_;
  hook_->after_step(obs_, final_obs_, rewards_, done_);
}

void VecEnv::reset_copy(int c) {
  // A copy's agents' columns are contiguous: one agent-major span for all of them.
  const int agents = agents_[c];
  envs_[c]->reset(seeds_[c], std::span<float>(obs_.col(first_slot_[c]).data(),
                                              static_cast<size_t>(obs_dim_) * agents));
  copy_info(c);
}

void VecEnv::step(const Eigen::Ref<const Eigen::MatrixXf>& actions) {
  if (actions.rows() != act_dim_ || actions.cols() != num_envs())
    throw std::invalid_argument("VecEnv::step: actions must be " + std::to_string(act_dim_) +
                                " x " + std::to_string(num_envs()) + ", got " +
                                std::to_string(actions.rows()) + " x " +
                                std::to_string(actions.cols()));
  last_actions_ = actions;
  if (!split_.empty()) {
    // Every started step is finished, also when one copy fails: a copy left with a reply
    // unread would read it as the answer to its next request. The first error is rethrown. A
    // copy that hung past a Ctrl-C (Interrupted, core/worker_wait.hpp) ends the run: the others
    // are not waited for, each for its own grace period.
    std::exception_ptr error;
    bool interrupted = false;
    int started = 0;
    try {
      for (; started < num_copies(); ++started) {
        const int first = first_slot_[started], agents = agents_[started];
        if (agents > 1)
          split_[started]->start_step_agents(std::span<const float>(
              actions.col(first).data(), static_cast<size_t>(act_dim_) * agents));
        else
          split_[started]->start_step(std::span<const float>(actions.col(first).data(), act_dim_));
      }
    } catch (...) {
      error = std::current_exception();
    }
    for (int c = 0; c < started && !interrupted; ++c) {
      try {
        const int first = first_slot_[c], agents = agents_[c];
        if (agents > 1) {
          split_[c]->finish_step_agents(
              std::span<float>(obs_.col(first).data(), static_cast<size_t>(obs_dim_) * agents),
              std::span<StepResult>(agent_results_.data(), static_cast<size_t>(agents)));
          if (!error) finish_agents(c);
        } else {
          const StepResult r =
              split_[c]->finish_step(std::span<float>(obs_.col(first).data(), obs_dim_));
          if (!error) finish_copy(c, r);
        }
      } catch (const Interrupted&) {
        interrupted = true;
        error = std::current_exception();
      } catch (...) {
        if (!error) error = std::current_exception();
      }
    }
    if (error) std::rethrow_exception(error);
  } else {
    step_copies(actions);
  }
  if (hook_) run_step_hook();
}

void VecEnv::step_copies(const Eigen::Ref<const Eigen::MatrixXf>& actions) {
  if (parallel_) {
    // Each part touches copy c's env and its own columns, flags, info and reset only.
    pool_->run(num_copies(), [&](int c) { step_copy(c, actions); });
    return;
  }
  const bool may_go_parallel = independent_copies_ && pool_ != nullptr && pool_->threads() > 1 &&
                               num_copies() > 1 && num_envs() == num_copies();
  if (!may_go_parallel || timed_steps_ >= kTimedSteps) {
    for (int c = 0; c < num_copies(); ++c) step_copy(c, actions);
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  for (int c = 0; c < num_copies(); ++c) step_copy(c, actions);
  timed_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (++timed_steps_ == kTimedSteps)
    parallel_ = timed_seconds_ / kTimedSteps >= parallel_step_seconds_;
}

void VecEnv::step_copy(int c, const Eigen::Ref<const Eigen::MatrixXf>& actions) {
  if (agents_[c] > 1) {
    step_agents(c, actions);
    return;
  }
  const int i = first_slot_[c];
  finish_copy(c, envs_[c]->step(std::span<const float>(actions.col(i).data(), act_dim_),
                                std::span<float>(obs_.col(i).data(), obs_dim_)));
}

void VecEnv::finish_copy(int c, const StepResult& r) {
  const int i = first_slot_[c];
  const std::span<float> obs(obs_.col(i).data(), obs_dim_);
  rewards_[i] = r.reward;
  terminated_[i] = r.terminated;
  truncated_[i] = r.truncated;
  copy_info(c);
  if (r.terminated || r.truncated) {
    final_obs_.col(i) = obs_.col(i);
    envs_[c]->reset(std::nullopt, obs);
  } else {
    final_obs_.col(i).setConstant(std::numeric_limits<float>::quiet_NaN());
  }
}

// One step of every agent of copy c (Env::step_agents): each agent's reward and flags go to
// its own column; the copy resets when its agents' episode ends, which must be all at once.
void VecEnv::step_agents(int c, const Eigen::Ref<const Eigen::MatrixXf>& actions) {
  const int first = first_slot_[c];
  const int agents = agents_[c];
  const std::span<float> obs(obs_.col(first).data(), static_cast<size_t>(obs_dim_) * agents);
  const std::span<StepResult> results(agent_results_.data(), static_cast<size_t>(agents));
  envs_[c]->step_agents(
      std::span<const float>(actions.col(first).data(), static_cast<size_t>(act_dim_) * agents),
      obs, results);
  finish_agents(c);
}

// After copy c's agents stepped (their results in agent_results_): rewards, flags, info, and
// the reset when their episode ended.
void VecEnv::finish_agents(int c) {
  const int first = first_slot_[c];
  const int agents = agents_[c];
  const std::span<float> obs(obs_.col(first).data(), static_cast<size_t>(obs_dim_) * agents);
  const std::span<StepResult> results(agent_results_.data(), static_cast<size_t>(agents));
  int ended = 0;
  for (int a = 0; a < agents; ++a) {
    rewards_[first + a] = results[a].reward;
    terminated_[first + a] = results[a].terminated;
    truncated_[first + a] = results[a].truncated;
    ended += results[a].terminated || results[a].truncated;
  }
  if (ended != 0 && ended != agents)
    throw std::runtime_error(envs_[c]->id() + ": " + std::to_string(ended) + " of " +
                             std::to_string(agents) +
                             " agents ended their episode; rlrun's multi-agent envs end all "
                             "agents together (include/rlrun/env.hpp)");
  copy_info(c);
  if (ended) {
    final_obs_.middleCols(first, agents) = obs_.middleCols(first, agents);
    envs_[c]->reset(std::nullopt, obs);
  } else {
    final_obs_.middleCols(first, agents).setConstant(std::numeric_limits<float>::quiet_NaN());
  }
}

bool VecEnv::can_save_state() const {
  for (const EnvPtr& env : envs_)
    if (!env->can_save_state()) return false;
  return true;
}

void VecEnv::write_state(StateWriter& out) const {
  for (int i = 0; i < num_copies(); ++i) {
    StateWriter env_out = out.sub(std::to_string(i));
    envs_[i]->write_state(env_out);
  }
  put_matrix(out, "obs", obs_);
  std::vector<uint64_t> pending(seeds_.size());
  std::vector<int64_t> has_pending(seeds_.size());
  for (size_t i = 0; i < seeds_.size(); ++i) {
    pending[i] = seeds_[i].value_or(0);
    has_pending[i] = seeds_[i].has_value();
  }
  out.put_vector("pending_seed", pending);
  out.put_vector("has_pending_seed", has_pending);
}

void VecEnv::read_state(const StateReader& in) {
  for (int i = 0; i < num_copies(); ++i) {
    envs_[i]->read_state(in.sub(std::to_string(i)));
    copy_info(i);
  }
  get_matrix(in, "obs", obs_);
  const auto pending = in.get_span<uint64_t>("pending_seed", num_copies());
  const auto has_pending = in.get_span<int64_t>("has_pending_seed", num_copies());
  for (int i = 0; i < num_copies(); ++i)
    seeds_[i] = has_pending[i] ? std::optional<uint64_t>(pending[i]) : std::nullopt;
  final_obs_.setConstant(std::numeric_limits<float>::quiet_NaN());
  rewards_.setZero();
  std::fill(terminated_.begin(), terminated_.end(), 0);
  std::fill(truncated_.begin(), truncated_.end(), 0);
}

void VecEnv::copy_info(int i) {
  const Info& src = envs_[i]->info();
  Info& dst = infos_[i];
  // Keys are declared when an env is built, so this branch runs once per env; an env that
  // declares a key late costs one allocation here, never a wrong value.
  if (dst.keys().size() != src.keys().size()) {
    dst = Info();
    for (const auto& key : src.keys()) dst.add_key(key);
  }
  for (size_t k = 0; k < src.values().size(); ++k)
    dst.set(static_cast<int>(k), src.get(static_cast<int>(k)));
}

}  // namespace rlrun
