#pragma once
// Reacher-v4: Gymnasium 1.0's gymnasium/envs/mujoco/reacher_v4.py. A two-link planar arm
// (scenarios/mujoco/reacher.xml) brings its fingertip to a target placed at random at reset.
//
//   observation  Box(11,): cos and sin of the two arm angles, the target's x, y (qpos[2:]), the
//                arm's angular velocities (qvel[:2]), fingertip - target (world x, y, z)
//   action       Box(-1, 1, (2,)): torques of joint0 (shoulder) and joint1 (elbow)
//   reward       -|fingertip - target| - sum(action^2), measured BEFORE the step is simulated
//                (Gymnasium's order: the reward is that of the state the action is taken in)
//   reset        qpos = init + U(-0.1, 0.1); the target (qpos[2:]) drawn U(-0.2, 0.2) per axis
//                until its distance from the centre is < 0.2; qvel = init + U(-0.005, 0.005),
//                the target's 0
//   info         reward_dist, reward_ctrl
//   time limit   50 steps
#include <array>

#include "rlrun/core/trusted_values.hpp"
#include "rlrun/envs/mujoco/mujoco_env.hpp"

namespace rlrun::mujoco {

class Reacher : public MujocoEnv {
 public:
  // Gymnasium's v4 constructor takes only MujocoEnv's rendering kwargs.
  struct Config {
    SimulatorInput xml_file;  // "" = the shipped reacher.xml

    template <class V>
    void visit(V& v) {
      v("xml_file", xml_file,
        "another MuJoCo model (MJCF) of the same joints and bodies; empty = shipped");
    }
  };

  Reacher() : Reacher(Config{}) {}
  explicit Reacher(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  void observe(std::span<float> obs) const override;

 private:
  void reset_model(Rng& rng) override;
  // get_body_com("fingertip") - get_body_com("target").
  std::array<double, 3> fingertip_to_target() const;

  int fingertip_, target_;
  int key_reward_dist_, key_reward_ctrl_;
};

}  // namespace rlrun::mujoco
