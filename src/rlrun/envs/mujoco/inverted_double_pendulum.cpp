#include "rlrun/envs/mujoco/inverted_double_pendulum.hpp"

#include <cmath>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/mujoco/model_shape.hpp"
#include "rlrun/envs/mujoco/numpy_math.hpp"

namespace rlrun::mujoco {

namespace {

constexpr int kFrameSkip = 5;
constexpr ModelShape kShape{.nq = 3, .nv = 3, .nu = 1};
constexpr double kClip = 10.0;

std::string model_file(const InvertedDoublePendulum::Config& config) {
  return model_path(config.xml_file.value, "inverted_double_pendulum.xml");
}

}  // namespace

InvertedDoublePendulum::InvertedDoublePendulum(const Config& config)
    : MujocoEnv("InvertedDoublePendulum-v4", model_file(config), kFrameSkip, 11) {
  require_shape(model(), kShape, id(), model_file(config));
  // Gymnasium reads data.site_xpos[0]: the model's first site, the upper pole's tip.
  if (model().nsite < 1)
    throw ConfigError(model_file(config) + ": " + id() +
                      " needs a model with a site (the upper pole's tip); this one has none");
  set_default_camera(
      {.trackbodyid = 0, .distance = 4.1225, .lookat = {{0.0, 0.0, 0.12250000000000005}}});
}

void InvertedDoublePendulum::reset_model(Rng& rng) {
  const std::vector<double> qpos = uniform_around(init_qpos(), -0.1, 0.1, rng);
  const std::vector<double> qvel = normal_around(init_qvel(), 0.1, rng);
  set_state(qpos, qvel);
}

void InvertedDoublePendulum::observe(std::span<float> obs) const {
  const std::span<const double> angles = qpos().subspan(1);
  ObservationWriter out(obs);
  out.put(qpos()[0]);
  for (double angle : angles) out.put(std::sin(angle));
  for (double angle : angles) out.put(std::cos(angle));
  const std::span<const double> constraint_forces(data().qfrc_constraint,
                                                  static_cast<size_t>(model().nv));
  out.put_clipped(qvel(), -kClip, kClip).put_clipped(constraint_forces, -kClip, kClip);
}

StepResult InvertedDoublePendulum::step(std::span<const float> action, std::span<float> obs) {
  if (!do_simulation(action)) return end_unstable(obs);
  observe(obs);
  const double x = data().site_xpos[0];
  const double y = data().site_xpos[2];
  // The Python computes with NumPy float64 scalars: x**2 is pow(x, 2.0) (numpy_math.hpp).
  const double dist_penalty = 0.01 * scalar_squared(x) + scalar_squared(y - 2.0);
  const double v1 = qvel()[1], v2 = qvel()[2];
  const double vel_penalty = 1e-3 * scalar_squared(v1) + 5e-3 * scalar_squared(v2);
  const double alive_bonus = 10.0;
  return {alive_bonus - dist_penalty - vel_penalty, y <= 1.0, false};
}

}  // namespace rlrun::mujoco
