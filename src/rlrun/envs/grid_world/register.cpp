// The tutorial's wrapped GridWorld.
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/grid_world/grid_world.hpp"

namespace rlrun::envs {

void register_grid_world(EnvEntries& out) {
  const size_t first = out.size();
  // No TimeLimit: GridWorld truncates itself after max_steps, with its timeout penalty.
  out.push_back(make_env_entry<GridWorld>("GridWorld-v0",
                                          "walk a 5x5 grid to the far corner; MultiDiscrete obs "
                                          "(OneHotObservation for DQN/SAC/TD3/DDPG)",
                                          0));
  // Steps of copies may run on several threads at once: each copy is its own grid position and RNG.
  mark_independent_copies(out, first);
}

}  // namespace rlrun::envs
