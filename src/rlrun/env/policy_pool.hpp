#pragma once
// Self-play against past selves (issue 45; the opponent sampling of OpenAI's and SB3 users'
// self-play setups: Bansal et al. 2018, "Emergent Complexity via Multi-Agent Competition"):
// training code snapshots the learner's policy every so many steps into a pool, and an env
// that plays a two-player game samples its opponent for each episode from the pool — the
// latest snapshot with probability `latest_probability`, otherwise one of the older ones
// uniformly.
//
// This is the hand-off between the two sides without either depending on the other: the
// trainer (runtime/run/self_play_callback) fills a PolicyPool with FrozenPolicy objects, and
// hands the pool to every env copy whose unwrapped env is a PlaysAgainstPool; the env
// (envs/board_games) reads it. Snapshots are only added between VecEnv steps, while no copy
// steps, and a FrozenPolicy is const and thread-safe, so copies stepping on several threads
// read the pool at once and the games do not depend on the thread count.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "rlrun/rng.hpp"

namespace rlrun {

// A frozen policy over a Discrete action space: its logits (unnormalised log-probabilities)
// for one observation, as the policy network computes them before masking. Thread-safe.
class FrozenPolicy {
 public:
  virtual ~FrozenPolicy() = default;
  virtual int num_actions() const = 0;
  virtual void logits(std::span<const float> obs, std::span<float> out) const = 0;
};

struct PolicySnapshot {
  int64_t id = 0;         // 0, 1, 2, ... in the order taken (kept in checkpoints)
  int64_t timesteps = 0;  // the learner's num_timesteps when it was taken
  std::shared_ptr<const FrozenPolicy> policy;
};

class PolicyPool {
 public:
  // Throws std::invalid_argument unless capacity >= 1 and latest_probability is in [0, 1].
  PolicyPool(int capacity, double latest_probability);

  // Adds a snapshot (ids must increase) and drops the oldest beyond the capacity.
  void add(PolicySnapshot snapshot);
  bool empty() const { return snapshots_.empty(); }
  const std::vector<PolicySnapshot>& snapshots() const { return snapshots_; }
  const PolicySnapshot& latest() const { return snapshots_.back(); }
  int capacity() const { return capacity_; }
  double latest_probability() const { return latest_probability_; }
  // One opponent: the latest with latest_probability, else one of the older snapshots
  // uniformly (the latest when it is the only one). Draws exactly two numbers from `rng`
  // (uniform, then below) whatever the pool holds, so an env's stream does not depend on how
  // full the pool is. Throws std::logic_error on an empty pool.
  const PolicySnapshot& sample(Rng& rng) const;
  // The snapshot with this id among the pool's and the retired ones, or nullptr.
  const PolicySnapshot* find(int64_t id) const;
  // A snapshot no longer sampled that an unfinished game of a resumed run still plays against:
  // find() sees it, sample() does not.
  void add_retired(PolicySnapshot snapshot);

 private:
  int capacity_;
  double latest_probability_;
  std::vector<PolicySnapshot> snapshots_;  // oldest first
  std::vector<PolicySnapshot> retired_;
};

// An env that can play against policies of a pool (TicTacToe-v0 and ConnectFour-v0 with
// `opponent: self_play`). Found through Env::unwrapped() by whoever owns the pool.
class PlaysAgainstPool {
 public:
  virtual ~PlaysAgainstPool() = default;
  // The pool the env samples its opponents from, from the next episode on (shared; the owner
  // adds snapshots between steps).
  virtual void set_policy_pool(std::shared_ptr<const PolicyPool> pool) = 0;
  // Whether this env's settings ask for a pool opponent (opponent: self_play).
  virtual bool wants_policy_pool() const = 0;
  // The id of the snapshot the current game plays against, or -1.
  virtual int64_t pool_snapshot_in_use() const = 0;
};

}  // namespace rlrun
