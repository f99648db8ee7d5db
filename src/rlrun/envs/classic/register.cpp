// Gymnasium 1.0's classic control (gymnasium/envs/classic_control/*.py), with the time limits
// gymnasium.make applies (gymnasium/envs/__init__.py).
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/classic/acrobot.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/envs/classic/mountain_car.hpp"
#include "rlrun/envs/classic/mountain_car_continuous.hpp"
#include "rlrun/envs/classic/pendulum.hpp"

namespace rlrun::envs {

void register_classic(EnvEntries& out) {
  const size_t first = out.size();
  out.push_back(make_env_entry<CartPole>("CartPole-v1", "balance a pole on a cart; Discrete(2)",
                                         CartPole::kMaxEpisodeSteps));
  out.push_back(make_env_entry<Pendulum>(
      "Pendulum-v1", "swing up and hold a pendulum; Box(1) torque", Pendulum::kMaxEpisodeSteps));
  out.push_back(make_env_entry<MountainCar>("MountainCar-v0",
                                            "drive an underpowered car up a hill; Discrete(3)",
                                            MountainCar::kMaxEpisodeSteps));
  out.push_back(make_env_entry<MountainCarContinuous>(
      "MountainCarContinuous-v0", "mountain car with a continuous force; Box(1)",
      MountainCarContinuous::kMaxEpisodeSteps));
  out.push_back(make_env_entry<Acrobot>(
      "Acrobot-v1", "swing a two-link arm above a line; Discrete(3)", Acrobot::kMaxEpisodeSteps));
  // Steps of copies may run on several threads at once: each copy is its own few floats of state and its own RNG.
  mark_independent_copies(out, first);
}

}  // namespace rlrun::envs
