#pragma once
// rl-zoo's partially observable tasks (rl_zoo3/import_envs.py registers `<Name>NoVel-v<N>` for
// every env of MaskVelocityWrapper.velocity_indices in rl_zoo3/wrappers.py): the env as it is,
// with its velocity terms multiplied by 0 in every observation, so that a policy must infer
// them from the past (ppo_lstm.yml trains RecurrentPPO on them). The masking belongs to the env
// id (a model trained on CartPoleNoVel-v1 records that id), as in the zoo.
#include <string>
#include <vector>

#include "rlrun/env/env_entry.hpp"
#include "rlrun/env/wrapper.hpp"

namespace rlrun {

// observation * mask, mask 0 at `velocity_indices` and 1 elsewhere (MaskVelocityWrapper's
// ObservationWrapper.observation, in float32 as numpy's float32 * float32).
class MaskVelocity : public Wrapper {
 public:
  // Throws std::invalid_argument for a non-Box observation or an index outside it.
  MaskVelocity(EnvPtr inner, std::string id, const std::vector<int>& velocity_indices);

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  std::string id() const override { return id_; }
  // The masking is the env id's (CartPoleNoVel-v1 sees no velocities): a trajectory records,
  // and Python's predict takes, the masked observations, as rlrun.make gives them.
  bool belongs_to_env() const override { return true; }
  // The masked observation as a graph: a policy exported from such a model applies the mask to
  // the observations it is given.
  std::string export_observation(PolicyGraph& graph, const std::string& obs) const override;
  std::string export_action(PolicyGraph& graph, const std::string& action) const override;

 private:
  void apply(std::span<float> obs) const;

  std::string id_;
  std::vector<float> mask_;
};

// The entry of `<base name>NoVel-v<N>`: `base`'s kwargs, spaces, time limit and metrics, its
// env wrapped in MaskVelocity. Its baselines are not carried over (they read the velocities).
EnvEntry masked_velocity_entry(const EnvEntry& base, std::vector<int> velocity_indices);

// "CartPole-v1" -> "CartPoleNoVel-v1" (the zoo's `f"{name}NoVel-v{version}"`).
std::string no_velocity_id(const std::string& base_id);

}  // namespace rlrun
