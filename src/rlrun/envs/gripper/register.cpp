// Robot grasping on Bullet; episodes end by the scenario's episode_steps. The baseline is a
// scripted controller (eval --baseline scripted, eval/record --policy scripted).
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/gripper/gripper_lift.hpp"
#include "rlrun/envs/gripper/scripted_grasp_policy.hpp"

namespace rlrun::envs {

void register_gripper(EnvEntries& out) {
  const PolicyEntry scripted{"scripted",
                             "moves above the cube, descends, closes and lifts (solves the task)",
                             [](Env& env, const PolicyOptions&) {
                               return scripted_grasp_actions(env);
                             }};
  EnvEntry lift = make_env_entry<GripperLift>(
      "GripperLift-v0",
      "3D parallel-jaw gripper (Bullet): reach a cube, grasp it, lift it 5 cm; Box(4) dx dy dz grip",
      0);
  lift.policies.push_back(scripted);
  lift.metrics = {"is_success", "lift"};
  EnvEntry easy = make_env_entry<GripperLiftEasy>(
      "GripperLiftEasy-v0", "GripperLift-v0 starting just above the cube (close and lift)", 0);
  easy.policies.push_back(scripted);
  easy.metrics = lift.metrics;
  out.push_back(std::move(lift));
  out.push_back(std::move(easy));
}

}  // namespace rlrun::envs
