#pragma once
// Walker2d-v4: Gymnasium 1.0's gymnasium/envs/mujoco/walker2d_v4.py. A planar biped
// (scenarios/mujoco/walker2d.xml) walks forward; the episode ends when it falls (is unhealthy).
//
//   observation  Box(17,): qpos[1:] (rootz, rooty, the six leg angles), clip(qvel, -10, 10)
//                (9); with exclude_current_positions_from_observation false, Box(18,) with
//                rootx first
//   action       Box(-1, 1, (6,)): torques of thigh, leg, foot (right), then the left ones
//   reward       (forward_reward_weight * dx/dt + healthy) - ctrl_cost_weight * sum(action^2),
//                dx the change of rootx over the step (dt = 0.002 * frame_skip 4), healthy =
//                float(is_healthy or terminate_when_unhealthy) * healthy_reward
//   healthy      rootz inside healthy_z_range and rooty inside healthy_angle_range (open
//                intervals)
//   terminated   not healthy, when terminate_when_unhealthy
//   reset        qpos = init + U(-scale, scale), qvel = init + U(-scale, scale)
//   info         x_position, x_velocity
//   time limit   1000 steps
#include "rlrun/core/trusted_values.hpp"
#include "rlrun/envs/mujoco/mujoco_env.hpp"
#include "rlrun/envs/mujoco/range_kwarg.hpp"

namespace rlrun::mujoco {

class Walker2d : public MujocoEnv {
 public:
  struct Config {
    double forward_reward_weight = 1.0;
    double ctrl_cost_weight = 1e-3;
    double healthy_reward = 1.0;
    bool terminate_when_unhealthy = true;
    RangeKwarg healthy_z_range{0.8, 2.0};
    RangeKwarg healthy_angle_range{-1.0, 1.0};
    double reset_noise_scale = 5e-3;
    bool exclude_current_positions_from_observation = true;
    SimulatorInput xml_file;  // "" = the shipped walker2d.xml

    template <class V>
    void visit(V& v) {
      v("forward_reward_weight", forward_reward_weight, "weight of the forward velocity reward");
      v("ctrl_cost_weight", ctrl_cost_weight, "weight of the sum of squared actions");
      v("healthy_reward", healthy_reward, "reward per step while healthy");
      v("terminate_when_unhealthy", terminate_when_unhealthy,
        "end the episode when unhealthy (else the healthy reward is 0 there)");
      v("healthy_z_range", healthy_z_range, "[low, high] open range of rootz while healthy");
      v("healthy_angle_range", healthy_angle_range,
        "[low, high] open range of rooty (torso pitch) while healthy");
      v("reset_noise_scale", reset_noise_scale, "scale of the noise added to the reset state");
      v("exclude_current_positions_from_observation", exclude_current_positions_from_observation,
        "leave rootx out of the observation");
      v("xml_file", xml_file, "another MuJoCo model (MJCF) of the same joints; empty = shipped");
    }
  };

  Walker2d() : Walker2d(Config{}) {}
  explicit Walker2d(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  void observe(std::span<float> obs) const override;

 private:
  void reset_model(Rng& rng) override;
  // Gymnasium's is_healthy of the current state.
  bool is_healthy() const;

  Config config_;
  int key_x_position_, key_x_velocity_;
};

}  // namespace rlrun::mujoco
