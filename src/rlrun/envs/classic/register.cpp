// Gymnasium 1.0's classic control (gymnasium/envs/classic_control/*.py), with the time limits
// gymnasium.make applies (gymnasium/envs/__init__.py).
#include "rlrun/env/env_entry.hpp"
#include "rlrun/env/mask_velocity.hpp"
#include "rlrun/envs/classic/acrobot.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/envs/classic/mountain_car.hpp"
#include "rlrun/envs/classic/mountain_car_continuous.hpp"
#include "rlrun/envs/classic/pendulum.hpp"

#include <string>
#include <utility>
#include <vector>

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
  // rl-zoo's partially observable variants: the velocities of MaskVelocityWrapper's
  // velocity_indices masked to 0 (CartPole's x_dot and theta_dot, the cars' velocity, the
  // pendulum's angular velocity).
  const std::vector<std::pair<std::string, std::vector<int>>> velocities{
      {"CartPole-v1", {1, 3}},
      {"MountainCar-v0", {1}},
      {"MountainCarContinuous-v0", {1}},
      {"Pendulum-v1", {2}}};
  const size_t bases = out.size();
  for (const auto& [id, indices] : velocities)
    for (size_t i = first; i < bases; ++i)
      if (out[i].id == id) out.push_back(masked_velocity_entry(out[i], indices));
  // Steps of copies may run on several threads at once: each copy is its own few floats of state and its own RNG.
  mark_independent_copies(out, first);
}

}  // namespace rlrun::envs
