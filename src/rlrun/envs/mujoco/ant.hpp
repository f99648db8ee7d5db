#pragma once
// Ant-v4: Gymnasium 1.0's gymnasium/envs/mujoco/ant_v4.py. A four-legged walker
// (scenarios/mujoco/ant.xml) moves forward (+x); the episode ends when its torso leaves the
// healthy height range or the state is no longer finite.
//
//   observation  Box(27,): qpos[2:] (torso z, orientation quaternion, eight hinge angles), qvel
//                (14); exclude_current_positions_from_observation false: Box(29,) with torso x, y
//                first; use_contact_forces: 84 more, cfrc_ext of the 14 bodies (torque, force)
//                clipped to contact_force_range
//   action       Box(-1, 1, (8,)): torques of hip_4, ankle_4, hip_1, ankle_1, hip_2, ankle_2,
//                hip_3, ankle_3
//   reward       dx/dt + healthy_reward - ctrl_cost_weight * sum(action^2)
//                [- contact_cost_weight * sum(clipped cfrc_ext^2) with use_contact_forces], dx the
//                change of the torso body's x (data.xpos) over the step (dt = 0.01 * frame_skip 5);
//                healthy_reward is paid while healthy, or always when terminate_when_unhealthy
//   healthy      every qpos and qvel finite and low <= torso z <= high (healthy_z_range)
//   terminated   not healthy, when terminate_when_unhealthy
//   reset        qpos = init + U(-scale, scale), qvel = init + scale * N(0, 1)
//   info         reward_forward, reward_ctrl, reward_survive, x_position, y_position,
//                distance_from_origin, x_velocity, y_velocity, forward_reward; with
//                use_contact_forces reward_ctrl is minus the CONTACT cost (Gymnasium's v4 does so)
//   time limit   1000 steps
#include <vector>

#include "rlrun/core/trusted_values.hpp"
#include "rlrun/envs/mujoco/mujoco_env.hpp"
#include "rlrun/envs/mujoco/range_kwarg.hpp"

namespace rlrun::mujoco {

class Ant : public MujocoEnv {
 public:
  struct Config {
    double ctrl_cost_weight = 0.5;
    bool use_contact_forces = false;
    double contact_cost_weight = 5e-4;
    double healthy_reward = 1.0;
    bool terminate_when_unhealthy = true;
    RangeKwarg healthy_z_range{0.2, 1.0};
    RangeKwarg contact_force_range{-1.0, 1.0};
    double reset_noise_scale = 0.1;
    bool exclude_current_positions_from_observation = true;
    SimulatorInput xml_file;  // "" = the shipped ant.xml

    template <class V>
    void visit(V& v) {
      v("ctrl_cost_weight", ctrl_cost_weight, "weight of the sum of squared actions");
      v("use_contact_forces", use_contact_forces,
        "observe the clipped contact forces and pay their cost");
      v("contact_cost_weight", contact_cost_weight,
        "weight of the sum of squared clipped contact forces");
      v("healthy_reward", healthy_reward, "reward per step while healthy");
      v("terminate_when_unhealthy", terminate_when_unhealthy,
        "end the episode when unhealthy (else pay healthy_reward only while healthy)");
      v("healthy_z_range", healthy_z_range, "[low, high] torso height of a healthy ant");
      v("contact_force_range", contact_force_range, "[low, high] clip of the contact forces");
      v("reset_noise_scale", reset_noise_scale, "scale of the noise added to the reset state");
      v("exclude_current_positions_from_observation", exclude_current_positions_from_observation,
        "leave the torso's x and y out of the observation");
      v("xml_file", xml_file, "another MuJoCo model (MJCF) of the same joints; empty = shipped");
    }
  };

  Ant() : Ant(Config{}) {}
  explicit Ant(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  void observe(std::span<float> obs) const override;

  // Gymnasium's is_healthy: the state vector (qpos, qvel) finite, the torso's z in range.
  bool is_healthy() const;

 private:
  void reset_model(Rng& rng) override;
  std::span<const double> contact_forces() const;  // data.cfrc_ext, nbody x 6
  double contact_cost();  // contact_cost_weight * sum of squared clipped contact forces

  Config config_;
  int torso_;
  std::vector<double> clipped_;  // scratch of contact_cost
  int key_reward_forward_, key_reward_ctrl_, key_reward_survive_, key_x_position_, key_y_position_,
      key_distance_from_origin_, key_x_velocity_, key_y_velocity_, key_forward_reward_;
};

}  // namespace rlrun::mujoco
