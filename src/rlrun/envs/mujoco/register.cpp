// Gymnasium 1.0's MuJoCo tasks (gymnasium/envs/__init__.py, the v4 ids) on Debian's MuJoCo 2.2.2.
// The v5 ids need MuJoCo >= 2.3.3 (Gymnasium's own requirement), which Debian 12 does not have
// (docs/mujoco.md).
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/mujoco/ant.hpp"
#include "rlrun/envs/mujoco/half_cheetah.hpp"
#include "rlrun/envs/mujoco/hopper.hpp"
#include "rlrun/envs/mujoco/humanoid.hpp"
#include "rlrun/envs/mujoco/humanoid_standup.hpp"
#include "rlrun/envs/mujoco/inverted_double_pendulum.hpp"
#include "rlrun/envs/mujoco/inverted_pendulum.hpp"
#include "rlrun/envs/mujoco/pusher.hpp"
#include "rlrun/envs/mujoco/reacher.hpp"
#include "rlrun/envs/mujoco/swimmer.hpp"
#include "rlrun/envs/mujoco/walker2d.hpp"

namespace rlrun::envs {

void register_mujoco(EnvEntries& out) {
  const size_t first = out.size();
  out.push_back(make_env_entry<mujoco::HalfCheetah>(
      "HalfCheetah-v4",
      "MuJoCo planar cheetah running forward; Box(6) joint torques, 17 observations", 1000));
  out.push_back(make_env_entry<mujoco::Hopper>(
      "Hopper-v4",
      "MuJoCo planar one-legged hopper hopping forward; Box(3) joint torques, 11 observations",
      1000));
  out.push_back(make_env_entry<mujoco::Walker2d>(
      "Walker2d-v4", "MuJoCo planar biped walking forward; Box(6) joint torques, 17 observations",
      1000));
  out.push_back(make_env_entry<mujoco::Swimmer>(
      "Swimmer-v4",
      "MuJoCo three-link swimmer in a viscous fluid; Box(2) joint torques, 8 observations", 1000));
  out.push_back(make_env_entry<mujoco::InvertedPendulum>(
      "InvertedPendulum-v4",
      "MuJoCo cart keeping a pole upright; Box(1) cart force, 4 observations, +1 per step", 1000));
  out.push_back(make_env_entry<mujoco::InvertedDoublePendulum>(
      "InvertedDoublePendulum-v4",
      "MuJoCo cart keeping two stacked poles upright; Box(1) cart force, 11 observations", 1000));
  out.push_back(make_env_entry<mujoco::Reacher>(
      "Reacher-v4",
      "MuJoCo two-link arm reaching a random target; Box(2) joint torques, 11 observations", 50));
  out.push_back(make_env_entry<mujoco::Pusher>(
      "Pusher-v4",
      "MuJoCo seven-joint arm pushing a cylinder to a goal; Box(7) joint torques, 23 observations",
      100));
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
