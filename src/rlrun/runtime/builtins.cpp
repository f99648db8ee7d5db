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
#include "rlrun/wrappers/box_as_discrete.hpp"
#include "rlrun/wrappers/discrete_as_box.hpp"

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

  // Wrappers usable in `env.wrappers`, applied in order after the Monitor.
  r.add(make_wrapper_entry<DiscreteAsBox>(
      "DiscreteAsBox", "Box(-1, 1, (n,)) scores -> argmax action of a Discrete(n) env (SAC/TD3 on CartPole)"));
  r.add(make_wrapper_entry<BoxAsDiscrete>(
      "BoxAsDiscrete", "Discrete(bins^dims) grid over a Box action space (DQN on Pendulum)"));

  r.add(make_algorithm_entry<PPO>("PPO", "Proximal Policy Optimization (SB3 semantics); Discrete/Box actions"));
  r.add(make_algorithm_entry<A2C>("A2C", "Advantage Actor-Critic (SB3 semantics, RMSprop); Discrete/Box actions"));
  r.add(make_algorithm_entry<SAC>("SAC", "Soft Actor-Critic (SB3 semantics, learned entropy coefficient); Box actions"));
  r.add(make_algorithm_entry<DQN>("DQN", "Deep Q-Network (SB3 semantics, epsilon-greedy, Huber loss); Discrete actions"));
  r.add(make_algorithm_entry<TD3>("TD3", "Twin Delayed DDPG (SB3 semantics, clipped double-Q, delayed actor); Box actions"));
  r.add(make_algorithm_entry<DDPG>("DDPG", "Deep Deterministic Policy Gradient (SB3 semantics: TD3 without its tricks); Box actions"));
  return r;
}

}  // namespace

const Registry& builtin_registry() {
  static const Registry registry = make_builtins();
  return registry;
}

}  // namespace rlrun
