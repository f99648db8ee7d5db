#pragma once
// Self-play against a pool of past selves (issue 45): every `freq` total steps the learner's
// policy is frozen (its deterministic graph, Algorithm::export_policy, up to the logits:
// env/graph_policy.hpp) and added to a PolicyPool that every training env copy with
// `opponent: self_play` samples its opponents from (env/policy_pool.hpp). The first snapshot
// is the untrained policy at step 0.
//
// Snapshots are taken in on_step, between VecEnv steps, so no env copy is stepping; the games
// depend on the seed only, not on the thread count. Checkpoints hold every snapshot's model
// tensors (and those of snapshots an unfinished game still plays against), and a resumed run
// rebuilds them with an algorithm of the run's own configuration: model tensors of a
// checkpoint are read as untrusted as the model's own (the algorithm's load checks them).
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "rlrun/env/policy_pool.hpp"
#include "rlrun/runtime/experiment/self_play_config.hpp"
#include "rlrun/runtime/run/callback.hpp"

namespace rlrun {

class SelfPlayCallback : public Callback {
 public:
  // Throws UsageError when no training env plays against a pool (opponent: self_play), the
  // envs' observations pass through a wrapper that changes them (the snapshots see the env's
  // own), or the policy is not one categorical (ExportError's reason).
  SelfPlayCallback(TrainingContext& context, const SelfPlayConfig& config);

  bool on_step(int64_t num_timesteps) override;
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

  const PolicyPool& pool() const { return *pool_; }

 private:
  struct Snapshot {
    int64_t timesteps = 0;
    TensorMap model;  // Algorithm::save's tensors, for checkpoints
    std::shared_ptr<const FrozenPolicy> policy;
  };

  std::shared_ptr<const FrozenPolicy> freeze(const Algorithm& algorithm) const;
  void take_snapshot(int64_t num_timesteps);
  // Drops kept snapshots that are neither in the pool nor played by an unfinished game.
  void forget_unused();

  TrainingContext& context_;
  SelfPlayConfig config_;
  std::shared_ptr<PolicyPool> pool_;
  std::vector<PlaysAgainstPool*> players_;  // the env copies that sample from the pool
  std::map<int64_t, Snapshot> kept_;        // by snapshot id
  int64_t next_id_ = 0;
  int64_t next_snapshot_ = 0;  // num_timesteps of the next snapshot
};

}  // namespace rlrun
