// Gymnasium 1.0's MuJoCo tasks (gymnasium/envs/__init__.py, the v4 ids) on Debian's MuJoCo 2.2.2.
// The v5 ids need MuJoCo >= 2.3.3 (Gymnasium's own requirement), which Debian 12 does not have
// (docs/mujoco.md).
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/mujoco/half_cheetah.hpp"

namespace rlrun::envs {

void register_mujoco(EnvEntries& out) {
  const size_t first = out.size();
  out.push_back(make_env_entry<mujoco::HalfCheetah>(
      "HalfCheetah-v4",
      "MuJoCo planar cheetah running forward; Box(6) joint torques, 17 observations", 1000));
  // Steps of copies may run on several threads at once: each copy has its own mjData and RNG,
  // and reads its mjModel only; MuJoCo's process-wide hooks are set once, before any copy runs.
  mark_independent_copies(out, first);
}

}  // namespace rlrun::envs
