#include "rlrun/envs/mujoco/inverted_pendulum.hpp"

#include <algorithm>
#include <cmath>

#include "rlrun/envs/mujoco/model_shape.hpp"

namespace rlrun::mujoco {

namespace {

constexpr int kFrameSkip = 2;
constexpr ModelShape kShape{.nq = 2, .nv = 2, .nu = 1};
constexpr double kResetNoise = 0.01;
constexpr double kMaxAngle = 0.2;

std::string model_file(const InvertedPendulum::Config& config) {
  return model_path(config.xml_file.value, "inverted_pendulum.xml");
}

bool all_finite(std::span<const double> values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

}  // namespace

InvertedPendulum::InvertedPendulum(const Config& config)
    : MujocoEnv("InvertedPendulum-v4", model_file(config), kFrameSkip, 4) {
  require_shape(model(), kShape, id(), model_file(config));
  set_default_camera({.trackbodyid = 0, .distance = 2.04});
}

void InvertedPendulum::reset_model(Rng& rng) {
  const std::vector<double> qpos = uniform_around(init_qpos(), -kResetNoise, kResetNoise, rng);
  const std::vector<double> qvel = uniform_around(init_qvel(), -kResetNoise, kResetNoise, rng);
  set_state(qpos, qvel);
}

void InvertedPendulum::observe(std::span<float> obs) const {
  ObservationWriter(obs).put(qpos()).put(qvel());
}

StepResult InvertedPendulum::step(std::span<const float> action, std::span<float> obs) {
  if (!do_simulation(action)) return end_unstable(obs);
  observe(obs);
  // Gymnasium tests its float64 observation: the state itself, not the float32 copy.
  const bool terminated =
      !all_finite(qpos()) || !all_finite(qvel()) || std::abs(qpos()[1]) > kMaxAngle;
  return {1.0, terminated, false};
}

}  // namespace rlrun::mujoco
