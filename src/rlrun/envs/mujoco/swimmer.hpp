#pragma once
// Swimmer-v4: Gymnasium 1.0's gymnasium/envs/mujoco/swimmer_v4.py. Three capsules joined by two
// hinges (scenarios/mujoco/swimmer.xml) swim forward (+x) through a viscous fluid; nothing ends
// an episode but the time limit.
//
//   observation  Box(8,): qpos[2:] (heading, the two hinge angles), qvel (5); with
//                exclude_current_positions_from_observation false, Box(10,) with x, y first
//   action       Box(-1, 1, (2,)): torques of motor1_rot, motor2_rot
//   reward       forward_reward_weight * dx/dt - ctrl_cost_weight * sum(action^2), dx the
//                change of x (slider1) over the step (dt = 0.01 * frame_skip 4)
//   reset        qpos = init + U(-scale, scale), qvel = init + U(-scale, scale)
//   info         reward_fwd, reward_ctrl, x_position, y_position, distance_from_origin (of the
//                x, y position), x_velocity, y_velocity, forward_reward
//   time limit   1000 steps
#include "rlrun/core/trusted_values.hpp"
#include "rlrun/envs/mujoco/mujoco_env.hpp"

namespace rlrun::mujoco {

class Swimmer : public MujocoEnv {
 public:
  struct Config {
    double forward_reward_weight = 1.0;
    double ctrl_cost_weight = 1e-4;
    double reset_noise_scale = 0.1;
    bool exclude_current_positions_from_observation = true;
    SimulatorInput xml_file;  // "" = the shipped swimmer.xml

    template <class V>
    void visit(V& v) {
      v("forward_reward_weight", forward_reward_weight, "weight of the forward velocity reward");
      v("ctrl_cost_weight", ctrl_cost_weight, "weight of the sum of squared actions");
      v("reset_noise_scale", reset_noise_scale, "scale of the noise added to the reset state");
      v("exclude_current_positions_from_observation", exclude_current_positions_from_observation,
        "leave x and y out of the observation");
      v("xml_file", xml_file, "another MuJoCo model (MJCF) of the same joints; empty = shipped");
    }
  };

  Swimmer() : Swimmer(Config{}) {}
  explicit Swimmer(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  void observe(std::span<float> obs) const override;

 private:
  void reset_model(Rng& rng) override;

  Config config_;
  int key_reward_fwd_, key_reward_ctrl_, key_x_position_, key_y_position_,
      key_distance_from_origin_, key_x_velocity_, key_y_velocity_, key_forward_reward_;
};

}  // namespace rlrun::mujoco
