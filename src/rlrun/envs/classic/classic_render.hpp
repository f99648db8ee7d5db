#pragma once
// The pictures of the classic-control envs (ClassicSpec::draw, state_from_observation), drawn
// like Gymnasium's pygame code in <env>_render.cpp. `state` is the physical state in
// Gymnasium's order; `last_action` is the env's last action for its current state (Pendulum
// draws its torque), NaN for a state read from an observation.
#include <span>

#include "rlrun/frame.hpp"

namespace rlrun {

void draw_cartpole(std::span<const double> state, double last_action, Frame& frame);
void cartpole_state_from_observation(std::span<const float> obs, std::span<double> state);

void draw_pendulum(std::span<const double> state, double last_action, Frame& frame);
void pendulum_state_from_observation(std::span<const float> obs, std::span<double> state);

void draw_acrobot(std::span<const double> state, double last_action, Frame& frame);
void acrobot_state_from_observation(std::span<const float> obs, std::span<double> state);

// MountainCar-v0 (flag at 0.5) and MountainCarContinuous-v0 (flag at 0.45): one scene.
void draw_mountain_car(std::span<const double> state, double last_action, Frame& frame);
void draw_mountain_car_continuous(std::span<const double> state, double last_action, Frame& frame);
// Both observations are the state (position, velocity).
void mountain_car_state_from_observation(std::span<const float> obs, std::span<double> state);

}  // namespace rlrun
