// The course's 2D grasp task.
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/grasp2d/grasp2d.hpp"

namespace rlrun::envs {

void register_grasp2d(EnvEntries& out) {
  const size_t first = out.size();
  out.push_back(make_env_entry<Grasp2D>(
      "Grasp2D-v0",
      "move an arm to an object and close the gripper; Discrete(6): left right up down open close",
      Grasp2D::kMaxEpisodeSteps));
  // Steps of copies may run on several threads at once: each copy is its own state and RNG.
  mark_independent_copies(out, first);
}

}  // namespace rlrun::envs
