#pragma once
// HumanoidStandup-v4: Gymnasium 1.0's gymnasium/envs/mujoco/humanoidstandup_v4.py. The 3D biped
// of Humanoid-v4, lying on the floor (scenarios/mujoco/humanoidstandup.xml), is paid for raising
// its torso; nothing ends an episode but the time limit.
//
//   observation  Box(376,): qpos[2:] (22), qvel (23), cinert (14 bodies x 10), cvel (14 x 6),
//                qfrc_actuator (23), cfrc_ext (14 x 6), as Humanoid-v4's
//   action       Box(-0.4, 0.4, (17,)): torques of the 17 hinges
//   reward       torso z / timestep (0.003 s) - 0.1 * sum(ctrl^2)
//                - min(0.5e-6 * sum(cfrc_ext^2), 10) + 1, ctrl data.ctrl (the action in float64)
//   reset        qpos = init + U(-0.01, 0.01), qvel = init + U(-0.01, 0.01)
//   info         reward_linup, reward_quadctrl, reward_impact
//   time limit   1000 steps
// Gymnasium's v4 task has no kwargs of its own; rlrun's Config has xml_file only.
#include "rlrun/core/trusted_values.hpp"
#include "rlrun/envs/mujoco/mujoco_env.hpp"

namespace rlrun::mujoco {

class HumanoidStandup : public MujocoEnv {
 public:
  struct Config {
    SimulatorInput xml_file;  // "" = the shipped humanoidstandup.xml

    template <class V>
    void visit(V& v) {
      v("xml_file", xml_file, "another MuJoCo model (MJCF) of the same joints; empty = shipped");
    }
  };

  HumanoidStandup() : HumanoidStandup(Config{}) {}
  explicit HumanoidStandup(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  void observe(std::span<float> obs) const override;

 private:
  void reset_model(Rng& rng) override;

  int key_reward_linup_, key_reward_quadctrl_, key_reward_impact_;
};

}  // namespace rlrun::mujoco
