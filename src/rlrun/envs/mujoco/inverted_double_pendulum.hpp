#pragma once
// InvertedDoublePendulum-v4: Gymnasium 1.0's
// gymnasium/envs/mujoco/inverted_double_pendulum_v4.py. A cart on a rail
// (scenarios/mujoco/inverted_double_pendulum.xml) keeps two poles, hinged end to end, upright.
//
//   observation  Box(11,): cart x, sin and cos of the two hinge angles, clip(qvel, -10, 10) (3),
//                clip(qfrc_constraint, -10, 10) (3)
//   action       Box(-1, 1, (1,)): the force on the cart
//   reward       10 - (0.01 * x^2 + (y - 2)^2) - (1e-3 * v1^2 + 5e-3 * v2^2), (x, y) the
//                world x and height of the upper pole's tip (site "tip"), v1, v2 the hinges'
//                angular velocities
//   terminated   y <= 1
//   reset        qpos = init + U(-0.1, 0.1), qvel = init + 0.1 * N(0, 1)
//   info         none
//   time limit   1000 steps
#include "rlrun/core/trusted_values.hpp"
#include "rlrun/envs/mujoco/mujoco_env.hpp"

namespace rlrun::mujoco {

class InvertedDoublePendulum : public MujocoEnv {
 public:
  // Gymnasium's v4 constructor takes only MujocoEnv's rendering kwargs.
  struct Config {
    SimulatorInput xml_file;  // "" = the shipped inverted_double_pendulum.xml

    template <class V>
    void visit(V& v) {
      v("xml_file", xml_file,
        "another MuJoCo model (MJCF) of the same joints and tip site; empty = shipped");
    }
  };

  InvertedDoublePendulum() : InvertedDoublePendulum(Config{}) {}
  explicit InvertedDoublePendulum(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  void observe(std::span<float> obs) const override;

 private:
  void reset_model(Rng& rng) override;
};

}  // namespace rlrun::mujoco
