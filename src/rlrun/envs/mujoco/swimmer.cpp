#include "rlrun/envs/mujoco/swimmer.hpp"

#include <array>

#include "rlrun/envs/mujoco/model_shape.hpp"
#include "rlrun/envs/mujoco/numpy_math.hpp"

namespace rlrun::mujoco {

namespace {

constexpr int kFrameSkip = 4;
constexpr ModelShape kShape{.nq = 5, .nv = 5, .nu = 2};

std::string model_file(const Swimmer::Config& config) {
  return model_path(config.xml_file.value, "swimmer.xml");
}

}  // namespace

Swimmer::Swimmer(const Config& config)
    : MujocoEnv("Swimmer-v4", model_file(config), kFrameSkip,
                config.exclude_current_positions_from_observation ? 8 : 10),
      config_(config) {
  require_shape(model(), kShape, id(), model_file(config));
  // Gymnasium's Swimmer-v4 passes no DEFAULT_CAMERA_CONFIG: the model's "track" camera or
  // MuJoCo's free camera.
  Info& info = mutable_info();
  key_reward_fwd_ = info.add_key("reward_fwd");
  key_reward_ctrl_ = info.add_key("reward_ctrl");
  key_x_position_ = info.add_key("x_position");
  key_y_position_ = info.add_key("y_position");
  key_distance_from_origin_ = info.add_key("distance_from_origin");
  key_x_velocity_ = info.add_key("x_velocity");
  key_y_velocity_ = info.add_key("y_velocity");
  key_forward_reward_ = info.add_key("forward_reward");
}

void Swimmer::reset_model(Rng& rng) {
  const double scale = config_.reset_noise_scale;
  const std::vector<double> qpos = uniform_around(init_qpos(), -scale, scale, rng);
  const std::vector<double> qvel = uniform_around(init_qvel(), -scale, scale, rng);
  set_state(qpos, qvel);
}

void Swimmer::observe(std::span<float> obs) const {
  const size_t skip = config_.exclude_current_positions_from_observation ? 2 : 0;
  ObservationWriter(obs).put(qpos().subspan(skip)).put(qvel());
}

StepResult Swimmer::step(std::span<const float> action, std::span<float> obs) {
  const std::array<double, 2> before{qpos()[0], qpos()[1]};
  if (!do_simulation(action)) return end_unstable(obs);
  const std::array<double, 2> after{qpos()[0], qpos()[1]};
  const double x_velocity = (after[0] - before[0]) / dt();
  const double y_velocity = (after[1] - before[1]) / dt();
  const double forward_reward = config_.forward_reward_weight * x_velocity;
  const double ctrl_cost = config_.ctrl_cost_weight * sum_of_squares(action);
  observe(obs);
  Info& info = mutable_info();
  info.set(key_reward_fwd_, forward_reward);
  info.set(key_reward_ctrl_, -ctrl_cost);
  info.set(key_x_position_, after[0]);
  info.set(key_y_position_, after[1]);
  info.set(key_distance_from_origin_, euclidean_norm(after));
  info.set(key_x_velocity_, x_velocity);
  info.set(key_y_velocity_, y_velocity);
  info.set(key_forward_reward_, forward_reward);
  return {forward_reward - ctrl_cost, false, false};
}

}  // namespace rlrun::mujoco
