// MountainCarContinuous-v0's picture: gymnasium/envs/classic_control/
// continuous_mountain_car.py render() (MountainCar's, with the flag at 0.45).
#include "rlrun/envs/classic/mountain_car_continuous.hpp"
#include "rlrun/envs/classic/mountain_car_scene.hpp"

namespace rlrun {

void MountainCarContinuous::draw_state(std::span<const double> state, bool /*current*/,
                                       Frame& frame) const {
  draw_mountain_car_scene(frame, state[0], /*goal_position=*/0.45);
}

void MountainCarContinuous::state_from_observation(std::span<const float> obs,
                                                   std::span<double> state) const {
  state[0] = obs[0];  // the observation is the state
  state[1] = obs[1];
}

}  // namespace rlrun
