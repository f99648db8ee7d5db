// Gymnasium 1.0's MuJoCo tasks (gymnasium/envs/__init__.py, the v4 ids) on Debian's MuJoCo 2.2.2.
// The v5 ids need MuJoCo >= 2.3.3 (Gymnasium's own requirement), which Debian 12 does not have
// (docs/mujoco.md).
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/mujoco/ant.hpp"
#include "rlrun/envs/mujoco/half_cheetah.hpp"
#include "rlrun/envs/mujoco/humanoid.hpp"
#include "rlrun/envs/mujoco/humanoid_standup.hpp"

namespace rlrun::envs {

void register_mujoco(EnvEntries& out) {
  const size_t first = out.size();
  out.push_back(make_env_entry<mujoco::HalfCheetah>(
      "HalfCheetah-v4",
      "MuJoCo planar cheetah running forward; Box(6) joint torques, 17 observations", 1000));
  out.push_back(make_env_entry<mujoco::Ant>(
      "Ant-v4", "MuJoCo four-legged ant walking forward; Box(8) joint torques, 27 observations",
      1000));
  out.push_back(make_env_entry<mujoco::Humanoid>(
      "Humanoid-v4", "MuJoCo 3D humanoid walking forward; Box(17) joint torques, 376 observations",
      1000));
  out.push_back(make_env_entry<mujoco::HumanoidStandup>(
      "HumanoidStandup-v4",
      "MuJoCo 3D humanoid standing up from the floor; Box(17) joint torques, 376 observations",
      1000));
  // Steps of copies may run on several threads at once: each copy has its own mjData and RNG,
  // and reads its mjModel only; MuJoCo's process-wide hooks are set once, before any copy runs.
  mark_independent_copies(out, first);
}

}  // namespace rlrun::envs
