// Gymnasium's LunarLander (gymnasium/envs/box2d/lunar_lander.py) on Box2D, with
// the ids and time limit gymnasium/envs/__init__.py registers: LunarLander-v3
// and LunarLanderContinuous-v3 (the same env with kwargs continuous=True), 1000
// steps each. The baseline is Gymnasium's heuristic(env, s) (eval --baseline
// heuristic, eval/record --policy heuristic).
#include "rlrun/core/config_fields.hpp"
#include "rlrun/env/env_entry.hpp"
#include "rlrun/env/mask_velocity.hpp"
#include "rlrun/envs/lunar_lander/heuristic_policy.hpp"
#include "rlrun/envs/lunar_lander/lunar_lander.hpp"

namespace rlrun::envs {

namespace {

// LunarLanderContinuous-v3: LunarLander-v3 whose `continuous` defaults to true
// (a user's kwargs still override it, as with gymnasium.make's kwargs over the
// registered ones).
EnvEntry continuous_alias(const EnvEntry& discrete) {
  EnvEntry entry = discrete;
  entry.id = "LunarLanderContinuous-v3";
  entry.description = "LunarLander-v3 with continuous: true; Box(2) main and lateral throttles";
  auto defaults = [] {
    LunarLander::Config config;
    config.continuous = true;
    return config;
  };
  entry.parse = [defaults](const ConfigNode& kwargs) {
    LunarLander::Config config = defaults();
    ConfigReader reader(kwargs, {});
    config.visit(reader);
    reader.finish();
    return AnyConfig::of(config);
  };
  entry.params = [defaults] {
    LunarLander::Config config = defaults();
    ConfigDocumenter documenter;
    config.visit(documenter);
    return documenter.rows();
  };
  return entry;
}

}  // namespace

void register_lunar_lander(EnvEntries& out) {
  const size_t first = out.size();
  EnvEntry lander = make_env_entry<LunarLander>("LunarLander-v3",
                                                "land a Box2D lander on the pad (Gymnasium); "
                                                "Discrete(4): noop left main right",
                                                LunarLander::kMaxEpisodeSteps);
  lander.policies.push_back(
      {"heuristic", "Gymnasium's heuristic(env, s) controller (lands: returns > 200)",
       [](Env& env, const PolicyOptions&) { return lunar_lander_heuristic_actions(env); }});
  EnvEntry continuous = continuous_alias(lander);
  // rl-zoo's partially observable variants (MaskVelocityWrapper.velocity_indices: the
  // velocities x_dot, y_dot and the angular velocity).
  out.push_back(masked_velocity_entry(lander, {2, 3, 5}));
  out.push_back(masked_velocity_entry(continuous, {2, 3, 5}));
  out.push_back(std::move(lander));
  out.push_back(std::move(continuous));
  // Steps of copies may run on several threads at once: each copy is its own b2World and RNG
  // (Box2D's only process-wide variables are its profiling counters, b2_gjkCalls and the
  // like, which no result reads).
  mark_independent_copies(out, first);
}

}  // namespace rlrun::envs
