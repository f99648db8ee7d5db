// The ONLY file that names concrete envs, wrappers and algorithms (DESIGN.md §1).
#include "rlrun/runtime/builtins.hpp"

#include "rlrun/algos/a2c/a2c.hpp"
#include "rlrun/algos/ddpg/ddpg.hpp"
#include "rlrun/algos/dqn/dqn.hpp"
#include "rlrun/algos/ppo/ppo.hpp"
#include "rlrun/algos/sac/sac.hpp"
#include "rlrun/algos/td3/td3.hpp"
#include "rlrun/envs/classic/acrobot.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/envs/classic/mountain_car.hpp"
#include "rlrun/envs/classic/mountain_car_continuous.hpp"
#include "rlrun/envs/classic/pendulum.hpp"
#include "rlrun/envs/grasp2d/grasp2d.hpp"
#include "rlrun/envs/grid_world/grid_world.hpp"
#include "rlrun/envs/gripper/gripper_lift.hpp"
#include "rlrun/envs/probe/dict_reach.hpp"
#include "rlrun/envs/probe/identity_env.hpp"
#include "rlrun/envs/probe/simple_multi_obs.hpp"
#include "rlrun/envs/traffic/traffic_signal.hpp"
#include "rlrun/wrappers/box_as_discrete.hpp"
#include "rlrun/wrappers/clip_action.hpp"
#include "rlrun/wrappers/frame_stack.hpp"
#include "rlrun/wrappers/normalize_observation.hpp"
#include "rlrun/wrappers/normalize_reward.hpp"
#include "rlrun/wrappers/rescale_action.hpp"
#include "rlrun/wrappers/reward_shaping.hpp"
#include "rlrun/wrappers/transform_reward.hpp"
#include "rlrun/wrappers/discrete_as_box.hpp"
#include "rlrun/wrappers/one_hot_observation.hpp"

namespace rlrun {

namespace {

Registry make_builtins() {
  Registry r;
  // Classic control, Gymnasium 1.0 (gymnasium/envs/classic_control/*.py), with the time limits
  // gymnasium.make applies (gymnasium/envs/__init__.py).
  r.add(make_env_entry<CartPole>("CartPole-v1", "balance a pole on a cart; Discrete(2)",
                                 CartPole::kMaxEpisodeSteps));
  r.add(make_env_entry<Pendulum>("Pendulum-v1", "swing up and hold a pendulum; Box(1) torque",
                                 Pendulum::kMaxEpisodeSteps));
  r.add(make_env_entry<MountainCar>("MountainCar-v0",
                                    "drive an underpowered car up a hill; Discrete(3)",
                                    MountainCar::kMaxEpisodeSteps));
  r.add(make_env_entry<MountainCarContinuous>(
      "MountainCarContinuous-v0", "mountain car with a continuous force; Box(1)",
      MountainCarContinuous::kMaxEpisodeSteps));
  r.add(make_env_entry<Acrobot>("Acrobot-v1", "swing a two-link arm above a line; Discrete(3)",
                                Acrobot::kMaxEpisodeSteps));
  // Custom tasks (issue 6): the course's 2D grasp env and the tutorial's wrapped GridWorld.
  r.add(make_env_entry<Grasp2D>(
      "Grasp2D-v0",
      "move an arm to an object and close the gripper; Discrete(6): left right up down open close",
      Grasp2D::kMaxEpisodeSteps));
  // No TimeLimit: GridWorld truncates itself after max_steps, with its timeout penalty.
  r.add(make_env_entry<GridWorld>(
      "GridWorld-v0", "walk a 5x5 grid to the far corner; MultiDiscrete obs (OneHotObservation for DQN/SAC/TD3/DDPG)",
      0));

  // Traffic-signal control on the real SUMO (issue 7); episodes end by num_seconds.
  r.add(make_env_entry<TrafficSignal>(
      "TrafficSignal-v0",
      "one traffic light at a 4-arm intersection in SUMO; Discrete(4): N, S, E or W green",
      0));

  // Robot grasping on Bullet (issue 8); episodes end by the scenario's episode_steps.
  r.add(make_env_entry<GripperLift>(
      "GripperLift-v0",
      "3D parallel-jaw gripper (Bullet): reach a cube, grasp it, lift it 5 cm; Box(4) dx dy dz grip",
      0));
  r.add(make_env_entry<GripperLiftEasy>(
      "GripperLiftEasy-v0", "GripperLift-v0 starting just above the cube (close and lift)", 0));

  // --- envs/probe/: one env per Gymnasium space kind (issue 16), SB3's test envs
  // (stable_baselines3/common/envs/identity_env.py, multi_input_envs.py) and a Dict reach task.
  r.add(make_env_entry<IdentityDiscrete>(
      "IdentityEnv-v0", "probe: act the observed value; Discrete(4) obs = action space",
      IdentityEnv::kMaxEpisodeSteps));
  r.add(make_env_entry<IdentityBox>(
      "IdentityEnvBox-v0", "probe: act the observed value within eps; Box(-1, 1, (1,)) obs = action",
      IdentityEnv::kMaxEpisodeSteps));
  r.add(make_env_entry<IdentityMultiDiscrete>(
      "IdentityEnvMultiDiscrete-v0",
      "probe: act the observed values; MultiDiscrete([4 4]) obs = action space",
      IdentityEnv::kMaxEpisodeSteps));
  r.add(make_env_entry<IdentityMultiBinary>(
      "IdentityEnvMultiBinary-v0", "probe: act the observed bits; MultiBinary(4) obs = action space",
      IdentityEnv::kMaxEpisodeSteps));
  r.add(make_env_entry<DictReach>(
      "DictReach-v0", "probe: move a point to a goal; Dict obs {goal, position}, Box(2) action",
      DictReach::kMaxEpisodeSteps));
  r.add(make_env_entry<SimpleMultiObs>(
      "SimpleMultiObsEnv-v0",
      "probe: 4x4 ring grid, Dict obs {moves: MultiBinary, row: Discrete, vec: Box}; Discrete(4)",
      SimpleMultiObs::kMaxEpisodeSteps));
  // --- end of envs/probe/

  // Wrappers usable in `env.wrappers`, applied in order after the Monitor.
  r.add(make_wrapper_entry<DiscreteAsBox>(
      "DiscreteAsBox", "Box(-1, 1, (n,)) scores -> argmax action of a Discrete(n) env (SAC/TD3 on CartPole)"));
  r.add(make_wrapper_entry<BoxAsDiscrete>(
      "BoxAsDiscrete", "Discrete(bins^dims) grid over a Box action space (DQN on Pendulum)"));
  // Workflow wrappers (issue 4): SB3 VecNormalize halves (statistics stored in the model file),
  // Gymnasium's action/observation/reward wrappers, reward shaping from YAML.
  r.add(make_wrapper_entry<NormalizeObservation>(
      "NormalizeObservation", "running mean/std observation normalisation (SB3 VecNormalize norm_obs)"));
  r.add(make_wrapper_entry<NormalizeReward>(
      "NormalizeReward", "reward / running std of the discounted return (SB3 VecNormalize norm_reward)"));
  r.add(make_wrapper_entry<ClipAction>(
      "ClipAction", "clip actions to the env's Box bounds; agent sees Box(-inf, inf) (Gymnasium)"));
  r.add(make_wrapper_entry<RescaleAction>(
      "RescaleAction", "agent acts in Box(min_action, max_action), mapped onto the env's bounds (Gymnasium)"));
  r.add(make_wrapper_entry<FrameStack>(
      "FrameStack", "the last n_stack observations stacked, oldest first (SB3 VecFrameStack)"));
  r.add(make_wrapper_entry<TransformReward>(
      "TransformReward", "reward' = clip(scale * reward + offset, clip_min, clip_max)"));
  r.add(make_wrapper_entry<RewardShaping>(
      "RewardShaping", "adds YAML-configured terms to the reward (obs_above_for, obs_abs, action_sq, ...)"));
  r.add(make_wrapper_entry<OneHotObservation>(
      "OneHotObservation", "Discrete/MultiDiscrete/MultiBinary observations as SB3's one-hot Box"));

  r.add(make_algorithm_entry<PPO>("PPO", "Proximal Policy Optimization (SB3 semantics); Box/Discrete/MultiDiscrete/MultiBinary actions"));
  r.add(make_algorithm_entry<A2C>("A2C", "Advantage Actor-Critic (SB3 semantics, RMSprop); Box/Discrete/MultiDiscrete/MultiBinary actions"));
  r.add(make_algorithm_entry<SAC>("SAC", "Soft Actor-Critic (SB3 semantics, learned entropy coefficient); Box actions"));
  r.add(make_algorithm_entry<DQN>("DQN", "Deep Q-Network (SB3 semantics, epsilon-greedy, Huber loss); Discrete actions"));
  r.add(make_algorithm_entry<TD3>("TD3", "Twin Delayed DDPG (SB3 semantics, clipped double-Q, delayed actor); Box actions"));
  r.add(make_algorithm_entry<DDPG>("DDPG", "Deep Deterministic Policy Gradient (SB3 semantics: TD3 without its tricks); Box actions"));
  return r;
}

}  // namespace

Registry& mutable_builtin_registry() {
  static Registry registry = make_builtins();
  return registry;
}

const Registry& builtin_registry() { return mutable_builtin_registry(); }

}  // namespace rlrun
