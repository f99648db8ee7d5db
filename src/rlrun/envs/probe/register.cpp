// Probe envs: one per Gymnasium space kind, SB3's test envs
// (stable_baselines3/common/envs/identity_env.py, multi_input_envs.py, bit_flipping_env.py) and
// a Dict reach task.
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/probe/bit_flipping.hpp"
#include "rlrun/envs/probe/dict_reach.hpp"
#include "rlrun/envs/probe/identity_env.hpp"
#include "rlrun/envs/probe/simple_multi_obs.hpp"

namespace rlrun::envs {

void register_probe(EnvEntries& out) {
  const size_t first = out.size();
  out.push_back(make_env_entry<IdentityDiscrete>(
      "IdentityEnv-v0", "probe: act the observed value; Discrete(4) obs = action space",
      IdentityEnv::kMaxEpisodeSteps));
  out.push_back(make_env_entry<IdentityBox>(
      "IdentityEnvBox-v0",
      "probe: act the observed value within eps; Box(-1, 1, (1,)) obs = action",
      IdentityEnv::kMaxEpisodeSteps));
  out.push_back(make_env_entry<IdentityMultiDiscrete>(
      "IdentityEnvMultiDiscrete-v0",
      "probe: act the observed values; MultiDiscrete([4 4]) obs = action space",
      IdentityEnv::kMaxEpisodeSteps));
  out.push_back(make_env_entry<IdentityMultiBinary>(
      "IdentityEnvMultiBinary-v0",
      "probe: act the observed bits; MultiBinary(4) obs = action space",
      IdentityEnv::kMaxEpisodeSteps));
  out.push_back(make_env_entry<DictReach>(
      "DictReach-v0", "probe: move a point to a goal; Dict obs {goal, position}, Box(2) action",
      DictReach::kMaxEpisodeSteps));
  // SB3's BitFlippingEnv truncates itself after max_steps: no registry TimeLimit.
  out.push_back(make_env_entry<BitFlipping>(
      "BitFlippingEnv-v0",
      "goal-conditioned probe for HER: flip n bits to ones; Dict obs {observation, "
      "achieved_goal, desired_goal}, sparse reward",
      0));
  out.push_back(make_env_entry<SimpleMultiObs>(
      "SimpleMultiObsEnv-v0",
      "probe: 4x4 ring grid, Dict obs {moves: MultiBinary, row: Discrete, vec: Box}; Discrete(4)",
      SimpleMultiObs::kMaxEpisodeSteps));
  // Steps of copies may run on several threads at once: each copy is its own state and RNG.
  mark_independent_copies(out, first);
}

}  // namespace rlrun::envs
