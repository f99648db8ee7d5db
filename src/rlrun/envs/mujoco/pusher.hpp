#pragma once
// Pusher-v4: Gymnasium 1.0's gymnasium/envs/mujoco/pusher_v4.py. A seven-joint arm
// (scenarios/mujoco/pusher.xml) pushes a cylinder, placed at random at reset, to a fixed goal.
//
//   observation  Box(23,): the arm's seven angles (qpos[:7]) and angular velocities (qvel[:7]),
//                the world positions of the fingertips (body tips_arm), the cylinder (object)
//                and the goal
//   action       Box(-2, 2, (7,)): torques of the seven arm joints
//   reward       -|object - goal| + 0.1 * -sum(action^2) + 0.5 * -|object - tips_arm|,
//                measured BEFORE the step is simulated (Gymnasium's order)
//   reset        the arm at init_qpos (no noise); the cylinder (qpos[-4:-2]) drawn from
//                U(-0.3, 0) x U(-0.2, 0.2) until it is more than 0.17 from the goal; the goal
//                (qpos[-2:]) at 0, 0; qvel = init + U(-0.005, 0.005), the last four 0
//   info         reward_dist, reward_ctrl
//   time limit   100 steps
#include <array>

#include "rlrun/core/trusted_values.hpp"
#include "rlrun/envs/mujoco/mujoco_env.hpp"

namespace rlrun::mujoco {

class Pusher : public MujocoEnv {
 public:
  // Gymnasium's v4 constructor takes only MujocoEnv's rendering kwargs.
  struct Config {
    SimulatorInput xml_file;  // "" = the shipped pusher.xml

    template <class V>
    void visit(V& v) {
      v("xml_file", xml_file,
        "another MuJoCo model (MJCF) of the same joints and bodies; empty = shipped");
    }
  };

  Pusher() : Pusher(Config{}) {}
  explicit Pusher(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  void observe(std::span<float> obs) const override;

 private:
  void reset_model(Rng& rng) override;
  // get_body_com(a) - get_body_com(b).
  std::array<double, 3> between(int a, int b) const;

  int tips_arm_, object_, goal_;
  int key_reward_dist_, key_reward_ctrl_;
};

}  // namespace rlrun::mujoco
