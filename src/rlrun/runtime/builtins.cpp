// The ONLY file that names concrete envs, wrappers and algorithms (DESIGN.md §1).
#include "rlrun/runtime/builtins.hpp"

#include "rlrun/algos/ppo/ppo.hpp"
#include "rlrun/envs/classic/acrobot.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/envs/classic/mountain_car.hpp"
#include "rlrun/envs/classic/mountain_car_continuous.hpp"
#include "rlrun/envs/classic/pendulum.hpp"

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

  r.add(make_algorithm_entry<PPO>("PPO", "Proximal Policy Optimization (SB3 semantics); Discrete/Box actions"));
  return r;
}

}  // namespace

const Registry& builtin_registry() {
  static const Registry registry = make_builtins();
  return registry;
}

}  // namespace rlrun
