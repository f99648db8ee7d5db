// Gymnasium's CarRacing-v3 (gymnasium/envs/__init__.py: max_episode_steps 1000,
// reward_threshold 900). The discrete version is the same id with continuous: false, as in
// Gymnasium.
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/car_racing/car_racing.hpp"
#include "rlrun/envs/car_racing/line_follower.hpp"

namespace rlrun::envs {

void register_car_racing(EnvEntries& out) {
  const size_t first = out.size();
  EnvEntry racing = make_env_entry<CarRacing>(
      "CarRacing-v3",
      "drive a Box2D car around a random track from 96x96 pixels (Gymnasium); Box(3) steer, gas, "
      "brake (continuous: false for Discrete(5))",
      CarRacing::kMaxEpisodeSteps);
  racing.policies.push_back(
      {"line-follower",
       "a scripted driver that reads the car and the track (pure pursuit of the centre line)",
       [](Env& env, const PolicyOptions&) { return line_follower_actions(env); }});
  out.push_back(std::move(racing));
  // Each copy is its own b2World, track, canvas and RNG, so copies may step on several threads.
  mark_independent_copies(out, first);
}

}  // namespace rlrun::envs
