#include "rlrun/envs/mujoco/half_cheetah.hpp"

#include "rlrun/envs/mujoco/model_shape.hpp"

namespace rlrun::mujoco {

namespace {

constexpr int kFrameSkip = 5;
constexpr ModelShape kShape{.nq = 9, .nv = 9, .nu = 6};

std::string model_file(const HalfCheetah::Config& config) {
  return model_path(config.xml_file.value, "half_cheetah.xml");
}

}  // namespace

HalfCheetah::HalfCheetah(const Config& config)
    : MujocoEnv("HalfCheetah-v4", model_file(config), kFrameSkip,
                config.exclude_current_positions_from_observation ? 17 : 18),
      config_(config) {
  require_shape(model(), kShape, id(), model_file(config));
  set_default_camera({.distance = 4.0});
  Info& info = mutable_info();
  key_x_position_ = info.add_key("x_position");
  key_x_velocity_ = info.add_key("x_velocity");
  key_reward_run_ = info.add_key("reward_run");
  key_reward_ctrl_ = info.add_key("reward_ctrl");
}

void HalfCheetah::reset_model(Rng& rng) {
  const double scale = config_.reset_noise_scale;
  const std::vector<double> qpos = uniform_around(init_qpos(), -scale, scale, rng);
  const std::vector<double> qvel = normal_around(init_qvel(), scale, rng);
  set_state(qpos, qvel);
}

void HalfCheetah::observe(std::span<float> obs) const {
  const size_t skip = config_.exclude_current_positions_from_observation ? 1 : 0;
  ObservationWriter(obs).put(qpos().subspan(skip)).put(qvel());
}

StepResult HalfCheetah::step(std::span<const float> action, std::span<float> obs) {
  const double x_before = qpos()[0];
  if (!do_simulation(action)) return end_unstable(obs);
  const double x_after = qpos()[0];
  const double x_velocity = (x_after - x_before) / dt();
  const double ctrl_cost = config_.ctrl_cost_weight * sum_of_squares(action);
  const double forward_reward = config_.forward_reward_weight * x_velocity;
  observe(obs);
  Info& info = mutable_info();
  info.set(key_x_position_, x_after);
  info.set(key_x_velocity_, x_velocity);
  info.set(key_reward_run_, forward_reward);
  info.set(key_reward_ctrl_, -ctrl_cost);
  return {forward_reward - ctrl_cost, false, false};
}

}  // namespace rlrun::mujoco
