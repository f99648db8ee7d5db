#pragma once
// HalfCheetah-v4: Gymnasium 1.0's gymnasium/envs/mujoco/half_cheetah_v4.py. A planar cheetah
// (scenarios/mujoco/half_cheetah.xml) runs forward; nothing ends an episode but the time limit.
//
//   observation  Box(17,): qpos[1:] (rootz, rooty, six leg angles), qvel (9); with
//                exclude_current_positions_from_observation false, Box(18,) with rootx first
//   action       Box(-1, 1, (6,)): torques of bthigh, bshin, bfoot, fthigh, fshin, ffoot
//   reward       forward_reward_weight * dx/dt - ctrl_cost_weight * sum(action^2), dx the
//                change of rootx over the step (dt = 0.01 * frame_skip 5)
//   reset        qpos = init + U(-scale, scale), qvel = init + scale * N(0, 1)
//   info         x_position, x_velocity, reward_run, reward_ctrl
//   time limit   1000 steps
#include "rlrun/core/trusted_values.hpp"
#include "rlrun/envs/mujoco/mujoco_env.hpp"

namespace rlrun::mujoco {

class HalfCheetah : public MujocoEnv {
 public:
  struct Config {
    double forward_reward_weight = 1.0;
    double ctrl_cost_weight = 0.1;
    double reset_noise_scale = 0.1;
    bool exclude_current_positions_from_observation = true;
    SimulatorInput xml_file;  // "" = the shipped half_cheetah.xml

    template <class V>
    void visit(V& v) {
      v("forward_reward_weight", forward_reward_weight, "weight of the forward velocity reward");
      v("ctrl_cost_weight", ctrl_cost_weight, "weight of the sum of squared actions");
      v("reset_noise_scale", reset_noise_scale, "scale of the noise added to the reset state");
      v("exclude_current_positions_from_observation", exclude_current_positions_from_observation,
        "leave rootx out of the observation");
      v("xml_file", xml_file, "another MuJoCo model (MJCF) of the same joints; empty = shipped");
    }
  };

  HalfCheetah() : HalfCheetah(Config{}) {}
  explicit HalfCheetah(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  void observe(std::span<float> obs) const override;

 private:
  void reset_model(Rng& rng) override;

  Config config_;
  int key_x_position_, key_x_velocity_, key_reward_run_, key_reward_ctrl_;
};

}  // namespace rlrun::mujoco
