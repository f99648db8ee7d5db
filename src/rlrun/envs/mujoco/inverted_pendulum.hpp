#pragma once
// InvertedPendulum-v4: Gymnasium 1.0's gymnasium/envs/mujoco/inverted_pendulum_v4.py. A cart on
// a rail (scenarios/mujoco/inverted_pendulum.xml) keeps a hinged pole upright.
//
//   observation  Box(4,): qpos (cart x, pole angle), qvel (their velocities)
//   action       Box(-3, 3, (1,)): the force on the cart
//   reward       1 per step (given also for the step that ends the episode)
//   terminated   an observation entry is not finite, or |pole angle| > 0.2 rad
//   reset        qpos = init + U(-0.01, 0.01), qvel = init + U(-0.01, 0.01)
//   info         none
//   time limit   1000 steps
#include "rlrun/core/trusted_values.hpp"
#include "rlrun/envs/mujoco/mujoco_env.hpp"

namespace rlrun::mujoco {

class InvertedPendulum : public MujocoEnv {
 public:
  // Gymnasium's v4 constructor takes only MujocoEnv's rendering kwargs.
  struct Config {
    SimulatorInput xml_file;  // "" = the shipped inverted_pendulum.xml

    template <class V>
    void visit(V& v) {
      v("xml_file", xml_file, "another MuJoCo model (MJCF) of the same joints; empty = shipped");
    }
  };

  InvertedPendulum() : InvertedPendulum(Config{}) {}
  explicit InvertedPendulum(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  void observe(std::span<float> obs) const override;

 private:
  void reset_model(Rng& rng) override;
};

}  // namespace rlrun::mujoco
