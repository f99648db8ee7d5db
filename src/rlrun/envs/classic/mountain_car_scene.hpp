#pragma once
// The picture shared by MountainCar-v0 and MountainCarContinuous-v0
// (gymnasium/envs/classic_control/mountain_car.py and continuous_mountain_car.py render(),
// identical but for the goal position): the hill curve, the car with two wheels, the flag.
#include "rlrun/frame.hpp"

namespace rlrun {

void draw_mountain_car_scene(Frame& frame, double position, double goal_position);

}  // namespace rlrun
