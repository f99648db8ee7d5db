#pragma once
// Pendulum-v1: gymnasium/envs/classic_control/pendulum.py (Gymnasium 1.0.0). Swing a
// frictionless pendulum up; torque clipped to [-2, 2], angular speed clipped to [-8, 8].
#include <limits>
#include <span>
#include <string>

#include "rlrun/envs/classic/classic_control_env.hpp"

namespace rlrun {

class Pendulum : public ClassicControlEnv {
 public:
  // gymnasium.make("Pendulum-v1", **kwargs) keyword arguments.
  struct Config {
    // Gravitational acceleration.
    double g = 10.0;

    template <class V>
    void visit(V& v) {
      v("g", g, "gravity in m/s^2");
    }
  };

  // Registered TimeLimit of Pendulum-v1 (gymnasium/envs/__init__.py).
  static constexpr int kMaxEpisodeSteps = 200;

  // Gymnasium's defaults. (A separate overload because a default argument `= {}` cannot
  // use Config's member initialisers inside the enclosing class.)
  Pendulum() : Pendulum(Config{}) {}
  explicit Pendulum(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  std::string id() const override { return "Pendulum-v1"; }
  // pendulum.py: screen_dim 500, render_fps 30.
  RenderSpec render_spec() const override { return {500, 500, 30}; }

  int state_dim() const override { return 2; }
  void get_state(std::span<double> state) const override;

  const Config& config() const { return config_; }

 protected:
  void sample_initial_state() override;
  void load_state(std::span<const double> state) override;
  void write_observation(std::span<float> obs) const override;
  void draw_state(std::span<const double> state, bool current, Frame& frame) const override;
  void state_from_observation(std::span<const float> obs,
                              std::span<double> state) const override;

 private:
  Config config_;
  double theta_ = 0.0;      // angle, 0 = upright; not wrapped (only the cost wraps it)
  double theta_dot_ = 0.0;  // angular velocity
  // Last clipped torque, only for the torque arrow (pendulum.py's self.last_u); NaN = None.
  double last_u_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace rlrun
