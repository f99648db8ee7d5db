#include "rlrun/envs/mujoco/walker2d.hpp"

#include "rlrun/envs/mujoco/model_shape.hpp"

namespace rlrun::mujoco {

namespace {

constexpr int kFrameSkip = 4;
constexpr ModelShape kShape{.nq = 9, .nv = 9, .nu = 6};
constexpr double kVelocityClip = 10.0;

std::string model_file(const Walker2d::Config& config) {
  return model_path(config.xml_file.value, "walker2d.xml");
}

}  // namespace

Walker2d::Walker2d(const Config& config)
    : MujocoEnv("Walker2d-v4", model_file(config), kFrameSkip,
                config.exclude_current_positions_from_observation ? 17 : 18),
      config_(config) {
  require_shape(model(), kShape, id(), model_file(config));
  set_default_camera(
      {.trackbodyid = 2, .distance = 4.0, .lookat = {{0.0, 0.0, 1.15}}, .elevation = -20.0});
  Info& info = mutable_info();
  key_x_position_ = info.add_key("x_position");
  key_x_velocity_ = info.add_key("x_velocity");
}

void Walker2d::reset_model(Rng& rng) {
  const double scale = config_.reset_noise_scale;
  const std::vector<double> qpos = uniform_around(init_qpos(), -scale, scale, rng);
  const std::vector<double> qvel = uniform_around(init_qvel(), -scale, scale, rng);
  set_state(qpos, qvel);
}

bool Walker2d::is_healthy() const {
  return config_.healthy_z_range.strictly_inside(qpos()[1]) &&
         config_.healthy_angle_range.strictly_inside(qpos()[2]);
}

void Walker2d::observe(std::span<float> obs) const {
  const size_t skip = config_.exclude_current_positions_from_observation ? 1 : 0;
  ObservationWriter(obs)
      .put(qpos().subspan(skip))
      .put_clipped(qvel(), -kVelocityClip, kVelocityClip);
}

StepResult Walker2d::step(std::span<const float> action, std::span<float> obs) {
  const double x_before = qpos()[0];
  if (!do_simulation(action)) return end_unstable(obs);
  const double x_after = qpos()[0];
  const double x_velocity = (x_after - x_before) / dt();
  const double ctrl_cost = config_.ctrl_cost_weight * sum_of_squares(action);
  const double forward_reward = config_.forward_reward_weight * x_velocity;
  const bool healthy = is_healthy();
  // float(is_healthy or terminate_when_unhealthy) * healthy_reward (0.0 * a negative weight is
  // -0.0, as in Python).
  const double healthy_reward =
      static_cast<double>(healthy || config_.terminate_when_unhealthy) * config_.healthy_reward;
  observe(obs);
  Info& info = mutable_info();
  info.set(key_x_position_, x_after);
  info.set(key_x_velocity_, x_velocity);
  const bool terminated = config_.terminate_when_unhealthy && !healthy;
  return {(forward_reward + healthy_reward) - ctrl_cost, terminated, false};
}

}  // namespace rlrun::mujoco
