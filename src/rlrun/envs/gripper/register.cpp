// Robot grasping on Bullet; episodes end by the scenario's episode_steps. The baselines are
// scripted controllers (eval --baseline scripted, eval/record --policy scripted).
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/gripper/gripper_goal_env.hpp"
#include "rlrun/envs/gripper/gripper_lift.hpp"
#include "rlrun/envs/gripper/scripted_goal_policy.hpp"
#include "rlrun/envs/gripper/scripted_grasp_policy.hpp"

namespace rlrun::envs {

namespace {

template <class E>
EnvEntry goal_task(const char* id, const char* description, const char* scripted) {
  EnvEntry entry = make_env_entry<E>(id, description, 0);
  entry.policies.push_back({"scripted", scripted, [](Env& env, const PolicyOptions&) {
                              return scripted_goal_actions(env);
                            }});
  entry.metrics = {"is_success", "distance"};
  return entry;
}

}  // namespace

void register_gripper(EnvEntries& out) {
  const size_t first = out.size();
  const PolicyEntry scripted{
      "scripted", "moves above the cube, descends, closes and lifts (solves the task)",
      [](Env& env, const PolicyOptions&) { return scripted_grasp_actions(env); }};
  EnvEntry lift = make_env_entry<GripperLift>("GripperLift-v0",
                                              "3D parallel-jaw gripper (Bullet): reach a cube, "
                                              "grasp it, lift it 5 cm; Box(4) dx dy dz grip",
                                              0);
  lift.policies.push_back(scripted);
  lift.metrics = {"is_success", "lift"};
  EnvEntry easy = make_env_entry<GripperLiftEasy>(
      "GripperLiftEasy-v0", "GripperLift-v0 starting just above the cube (close and lift)", 0);
  easy.policies.push_back(scripted);
  easy.metrics = lift.metrics;
  out.push_back(std::move(lift));
  out.push_back(std::move(easy));
  // panda-gym's goal tasks (GoalEnv: Dict obs, compute_reward for HER).
  out.push_back(goal_task<GripperReach>(
      "GripperReach-v0",
      "goal env (panda-gym Reach): move the fingertips to a goal; Dict obs, Box(3) dx dy dz",
      "moves the fingertips straight to the goal"));
  out.push_back(goal_task<GripperPush>(
      "GripperPush-v0",
      "goal env (panda-gym Push): push a 4 cm cube to a goal on the table; Box(3), closed fingers",
      "goes behind the cube on the goal's line, descends and pushes"));
  out.push_back(goal_task<GripperPickAndPlace>(
      "GripperPickAndPlace-v0",
      "goal env (panda-gym PickAndPlace): carry a cube to a goal, half in the air; Box(4) + grip",
      "grasps the cube, lifts it and carries it to the goal"));
  // Steps of copies may run on several threads at once: each copy is its own Bullet world and RNG.
  mark_independent_copies(out, first);
}

}  // namespace rlrun::envs
