#pragma once
// VecEnv: n envs stepped in lockstep, with Stable-Baselines3's DummyVecEnv semantics
// (stable_baselines3/common/vec_env/dummy_vec_env.py, base_vec_env.py):
//   * seed(s) makes the NEXT reset() reset env i with seed s + i; later resets, including the
//     automatic ones, pass no seed so each env continues its own stream.
//   * step() auto-resets every env whose episode ended (terminated || truncated) in the same
//     call: final_obs() column i holds the observation that ended the episode (SB3's
//     info["terminal_observation"]), obs() column i the new episode's first observation.
//   * info(i) is env i's Info of that step, copied before the auto-reset (SB3 keeps the
//     step's info dict; the reset info is separate).
// Observations and actions are one column per env (features x n_envs).
// All buffers are allocated in the constructor; step() does not allocate.
//
// Copies that share nothing (set_independent_copies: each its own simulator, RNG and wrappers)
// step at once on the run's thread pool (set_thread_pool) when a step is worth a hand-off,
// as EnvPool steps its envs: every copy writes only its own columns, so the batch is the same
// bits whichever thread stepped which copy.
//
// Multi-agent envs (Env::num_agents() > 1, include/rlrun/env.hpp) take one column per agent:
// a VecEnv of n copies of a k-agent env has n * k columns (num_envs()), and an algorithm sees
// k * n envs sharing one policy, as SuperSuit's pettingzoo_env_to_vec_env gives SB3. An env's
// agents end their episode together; the env is then reset as a whole. num_copies() and
// env(c) address the env copies themselves (monitors, statistics).
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "rlrun/core/thread_pool.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env/split_step.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

// Work on the whole batch after every copy has stepped or reset: what an SB3 VecEnvWrapper's
// step_wait() / reset() does on top of the per-env stacks. VecNormalize is one
// (wrappers/vec_normalize.hpp). Must not allocate.
class VecStepHook {
 public:
  virtual ~VecStepHook() = default;
  // After reset(): `obs` holds every env's first observation.
  virtual void after_reset(Eigen::MatrixXf& obs) = 0;
  // After step() and its auto-resets: `obs` as the algorithm will see it, `final_obs` the
  // finished episodes' last observations (columns where `done`), `rewards` the step's rewards.
  virtual void after_step(Eigen::MatrixXf& obs, Eigen::MatrixXf& final_obs,
                          Eigen::VectorXd& rewards, std::span<const uint8_t> done) = 0;
  // SB3 VecNormalize.normalize_obs / normalize_reward with the current statistics, for values
  // kept as the envs gave them (an off-policy algorithm's replay batches). Default: unchanged.
  virtual void normalize_obs(Eigen::Ref<Eigen::MatrixXf> /*obs*/) const {}
  virtual void normalize_rewards(Eigen::Ref<Eigen::RowVectorXf> /*rewards*/) const {}
};

class VecEnv {
 public:
  // Throws std::invalid_argument if `envs` is empty, holds a null env, or the envs disagree
  // on their observation or action space. When every copy's stack steps asynchronously (envs
  // in other processes, env/split_step.hpp), step() starts every copy's step before it
  // finishes any, so those processes run in parallel; the halves are finished in copy order,
  // so wrappers that share statistics across copies (NormalizeObservation) see the same
  // sequence as with whole steps. (Not threads: those would make that order vary.)
  explicit VecEnv(std::vector<EnvPtr> envs);
  VecEnv(VecEnv&&) noexcept;
  VecEnv& operator=(VecEnv&&) noexcept;
  ~VecEnv();

  // Columns: one per agent of every env copy (= the number of env copies for single-agent envs).
  int num_envs() const { return static_cast<int>(slot_env_.size()); }
  int num_copies() const { return static_cast<int>(envs_.size()); }
  const Space& observation_space() const { return envs_.front()->observation_space(); }
  const Space& action_space() const { return envs_.front()->action_space(); }

  // The next reset() seeds env copy i with seed + i (SB3 VecEnv.seed).
  void seed(uint64_t seed);

  // Resets every env; returns the observations (obs_dim x n_envs).
  const Eigen::MatrixXf& reset();
  // Steps every env with its column of `actions` (act_dim x n_envs) and auto-resets the
  // envs that finished. Throws std::invalid_argument on a wrong shape.
  void step(const Eigen::Ref<const Eigen::MatrixXf>& actions);

  const Eigen::MatrixXf& obs() const { return obs_; }
  // The actions of the last step() (act_dim x n_envs; empty before one): SB3's `actions` in a
  // callback's locals (python/src/py_training_session.cpp).
  const Eigen::MatrixXf& last_actions() const { return last_actions_; }
  const Eigen::VectorXd& rewards() const { return rewards_; }
  bool terminated(int i) const { return terminated_[i] != 0; }
  bool truncated(int i) const { return truncated_[i] != 0; }
  bool done(int i) const { return terminated(i) || truncated(i); }
  // Column i is the last observation of env i's finished episode when done(i); NaN otherwise.
  const Eigen::MatrixXf& final_obs() const { return final_obs_; }
  // SB3 VecNormalize.get_original_obs / get_original_reward: the last step's (or reset's)
  // values as the envs gave them, before the step hook changed them; obs(), final_obs() and
  // rewards() themselves without a hook. (After read_state they are not restored: callers
  // that need them across a resume keep their own.)
  const Eigen::MatrixXf& original_obs() const { return hook_ ? original_obs_ : obs_; }
  const Eigen::MatrixXf& original_final_obs() const {
    return hook_ ? original_final_obs_ : final_obs_;
  }
  const Eigen::VectorXd& original_rewards() const { return hook_ ? original_rewards_ : rewards_; }
  // Column i's info of the last step (or of the last reset(), before any step): its env
  // copy's info.
  const Info& info(int i) const { return infos_[slot_env_[i]]; }

  // Resume: every env's state under "<i>/", the current observations and pending seeds. A
  // restored VecEnv continues without reset(); can_save_state() is false when any env cannot
  // snapshot itself.
  bool can_save_state() const;
  void write_state(StateWriter& out) const;
  void read_state(const StateReader& in);

  // Runs `hook` after every reset() and step() from now on (single-agent copies only).
  void set_step_hook(std::unique_ptr<VecStepHook> hook);
  VecStepHook* step_hook() const { return hook_.get(); }

  // Whoever built the copies vouches that they share no state: no simulator, RNG, file or
  // statistics (runtime/experiment/env_factory.cpp decides from the env's entry and the wrappers). Then
  // step() may step them on the pool's threads at once. Off by default.
  void set_independent_copies(bool independent) { independent_copies_ = independent; }
  // The threads step() may use (null: the calling thread). Never changes a result.
  void set_thread_pool(ThreadPool* pool) { pool_ = pool; }
  // Whether step() now steps the copies on the pool: after its first kTimedSteps steps,
  // measured one copy after another, when a batch took at least parallel_step_seconds.
  bool steps_in_parallel() const { return parallel_; }
  // Tests: 0 steps copies on the pool whenever they may go there.
  void set_parallel_step_seconds(double seconds) { parallel_step_seconds_ = seconds; }
  static constexpr int kTimedSteps = 16;
  // A hand-off to the pool's workers and back costs a few microseconds (core/thread_pool.hpp);
  // below this a batch of steps is faster on one thread (8 CartPoles take ~3 us; 8
  // LunarLanders ~100 us).
  static constexpr double kParallelStepSeconds = 30e-6;

  // Env copy c (0 <= c < num_copies()).
  Env& env(int c) { return *envs_[c]; }
  const Env& env(int c) const { return *envs_[c]; }

 private:
  void copy_info(int i);
  void reset_copy(int c);
  void step_copy(int c, const Eigen::Ref<const Eigen::MatrixXf>& actions);
  // After copy c's step returned r: rewards, flags, info, and the auto-reset.
  void finish_copy(int c, const StepResult& r);
  void step_agents(int c, const Eigen::Ref<const Eigen::MatrixXf>& actions);
  void finish_agents(int c);
  void run_step_hook();
  // Steps every copy one after another, or at once on the pool once that is known to pay.
  void step_copies(const Eigen::Ref<const Eigen::MatrixXf>& actions);

  std::vector<EnvPtr> envs_;
  std::vector<int> first_slot_;  // env copy c's first column
  // Env copy c's agents, asked once: num_agents() is fixed for an env's life, and asking it
  // every step walks the whole wrapper chain (2 % of a PPO Pendulum run).
  std::vector<int> agents_;
  std::vector<int> slot_env_;              // column -> env copy
  std::vector<StepResult> agent_results_;  // step_agents() scratch, the most agents of a copy
  std::vector<std::optional<uint64_t>> seeds_;
  int obs_dim_ = 0;
  int act_dim_ = 0;
  Eigen::MatrixXf obs_;
  Eigen::MatrixXf last_actions_;
  Eigen::MatrixXf final_obs_;
  Eigen::VectorXd rewards_;
  // uint8_t rather than vector<bool> so that element access is a plain load.
  std::vector<uint8_t> terminated_;
  std::vector<uint8_t> truncated_;
  std::vector<Info> infos_;
  // Every copy steps asynchronously (env/split_step.hpp): start all steps, then finish them.
  std::vector<SplitStep*> split_;
  std::unique_ptr<VecStepHook> hook_;
  Eigen::MatrixXf original_obs_, original_final_obs_;  // with a hook: before it ran
  Eigen::VectorXd original_rewards_;
  std::vector<uint8_t> done_;  // terminated || truncated, for the hook
  bool independent_copies_ = false;
  ThreadPool* pool_ = nullptr;
  int timed_steps_ = 0;         // serial steps measured so far (up to kTimedSteps)
  double timed_seconds_ = 0.0;  // ... and their total time
  bool parallel_ = false;
  double parallel_step_seconds_ = kParallelStepSeconds;
};

}  // namespace rlrun
