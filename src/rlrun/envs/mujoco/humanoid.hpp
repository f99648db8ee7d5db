#pragma once
// Humanoid-v4: Gymnasium 1.0's gymnasium/envs/mujoco/humanoid_v4.py. A 3D biped
// (scenarios/mujoco/humanoid.xml) walks forward (+x) without falling; the episode ends when its
// torso leaves the healthy height range.
//
//   observation  Box(376,): qpos[2:] (22), qvel (23), cinert (14 bodies x 10), cvel (14 x 6),
//                qfrc_actuator (23), cfrc_ext (14 x 6); exclude_current_positions_from_observation
//                false: Box(378,) with the torso's x, y first
//   action       Box(-0.4, 0.4, (17,)): torques of the 17 hinges (humanoid.xml's actuators)
//   reward       forward_reward_weight * dx/dt + healthy_reward - ctrl_cost_weight * sum(ctrl^2),
//                dx the change of the x of the centre of mass (body_mass and data.xipos) over the
//                step (dt = 0.003 * frame_skip 5), ctrl data.ctrl (the action in float64, not
//                clipped); healthy_reward is paid while healthy, or always when
//                terminate_when_unhealthy
//   healthy      low < torso z < high (healthy_z_range, both strict)
//   terminated   not healthy, when terminate_when_unhealthy
//   reset        qpos = init + U(-scale, scale), qvel = init + U(-scale, scale)
//   info         reward_linvel, reward_quadctrl, reward_alive, x_position, y_position,
//                distance_from_origin, x_velocity, y_velocity, forward_reward (positions of the
//                centre of mass)
//   time limit   1000 steps
#include <array>

#include "rlrun/core/trusted_values.hpp"
#include "rlrun/envs/mujoco/mujoco_env.hpp"
#include "rlrun/envs/mujoco/range_kwarg.hpp"

namespace rlrun::mujoco {

class Humanoid : public MujocoEnv {
 public:
  struct Config {
    double forward_reward_weight = 1.25;
    double ctrl_cost_weight = 0.1;
    double healthy_reward = 5.0;
    bool terminate_when_unhealthy = true;
    RangeKwarg healthy_z_range{1.0, 2.0};
    double reset_noise_scale = 1e-2;
    bool exclude_current_positions_from_observation = true;
    SimulatorInput xml_file;  // "" = the shipped humanoid.xml

    template <class V>
    void visit(V& v) {
      v("forward_reward_weight", forward_reward_weight,
        "weight of the centre of mass's forward velocity");
      v("ctrl_cost_weight", ctrl_cost_weight, "weight of the sum of squared controls");
      v("healthy_reward", healthy_reward, "reward per step while healthy");
      v("terminate_when_unhealthy", terminate_when_unhealthy,
        "end the episode when unhealthy (else pay healthy_reward only while healthy)");
      v("healthy_z_range", healthy_z_range,
        "(low, high) torso height of a healthy humanoid, bounds excluded");
      v("reset_noise_scale", reset_noise_scale, "scale of the noise added to the reset state");
      v("exclude_current_positions_from_observation", exclude_current_positions_from_observation,
        "leave the torso's x and y out of the observation");
      v("xml_file", xml_file, "another MuJoCo model (MJCF) of the same joints; empty = shipped");
    }
  };

  Humanoid() : Humanoid(Config{}) {}
  explicit Humanoid(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  void observe(std::span<float> obs) const override;

  bool is_healthy() const;  // Gymnasium's: low < qpos[2] < high

 private:
  void reset_model(Rng& rng) override;
  // Gymnasium's mass_center: x and y of sum(body_mass * xipos, axis=0) / sum(body_mass).
  std::array<double, 2> mass_center() const;

  Config config_;
  double total_mass_;  // np.sum(model.body_mass)
  int key_reward_linvel_, key_reward_quadctrl_, key_reward_alive_, key_x_position_, key_y_position_,
      key_distance_from_origin_, key_x_velocity_, key_y_velocity_, key_forward_reward_;
};

// The part of the humanoid tasks' observation after qpos and qvel: cinert, cvel, qfrc_actuator,
// cfrc_ext (Humanoid-v4 and HumanoidStandup-v4 observe the same).
void put_body_dynamics(ObservationWriter& out, const mjModel& model, const mjData& data);

}  // namespace rlrun::mujoco
