// Gymnasium's BipedalWalker ids (gymnasium/envs/__init__.py): BipedalWalker-v3 with 1600
// steps, and BipedalWalkerHardcore-v3, the same class registered with kwargs
// {"hardcore": True} and 2000 steps. The baseline is Gymnasium's scripted walker.
#include "rlrun/core/config_fields.hpp"
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/bipedal_walker/bipedal_walker.hpp"
#include "rlrun/envs/bipedal_walker/walking_heuristic.hpp"

namespace rlrun::envs {

namespace {

// The hardcore alias's kwargs: BipedalWalker's, with hardcore true unless set.
struct HardcoreConfig : BipedalWalker::Config {
  HardcoreConfig() { hardcore = true; }
};

}  // namespace

void register_bipedal_walker(EnvEntries& out) {
  const size_t first = out.size();
  const PolicyEntry heuristic{
      "heuristic", "Gymnasium's scripted gait (BipedalWalkerHeuristics): walks on normal terrain",
      [](Env& env, const PolicyOptions&) { return walking_heuristic_actions(env); }};

  EnvEntry walker = make_env_entry<BipedalWalker>(
      "BipedalWalker-v3",
      "Box2D biped crossing rough terrain; Box(4) hip and knee torques, 24 observations with lidar",
      walker::kMaxEpisodeSteps);
  walker.policies.push_back(heuristic);

  EnvEntry hardcore = make_env_entry<BipedalWalker>(
      "BipedalWalkerHardcore-v3", "BipedalWalker-v3 with stumps, stairs and pits (hardcore: true)",
      walker::kMaxEpisodeStepsHardcore);
  hardcore.parse = [](const ConfigNode& kwargs) {
    return AnyConfig::of(BipedalWalker::Config(read_config<HardcoreConfig>(kwargs)));
  };
  hardcore.params = [] { return document_config<HardcoreConfig>(); };
  hardcore.policies.push_back(heuristic);

  out.push_back(std::move(walker));
  out.push_back(std::move(hardcore));
  // Steps of copies may run on several threads at once: each copy is its own b2World, terrain
  // and RNG (Box2D's only process-wide variables are its profiling counters, which no result
  // reads).
  mark_independent_copies(out, first);
}

}  // namespace rlrun::envs
