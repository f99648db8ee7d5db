#include "rlrun/envs/mujoco/ant.hpp"

#include <algorithm>
#include <cmath>

#include "rlrun/envs/mujoco/model_shape.hpp"

namespace rlrun::mujoco {

namespace {

constexpr int kFrameSkip = 5;
// The shipped model's sizes: 15 qpos (free joint 7, eight hinges), 14 qvel, 14 bodies.
constexpr ModelShape kShape{.nq = 15, .nv = 14, .nu = 8, .nbody = 14};

std::string model_file(const Ant::Config& config) {
  return model_path(config.xml_file.value, "ant.xml");
}

int observation_size(const Ant::Config& config) {
  const int skip = config.exclude_current_positions_from_observation ? 2 : 0;
  return kShape.nq - skip + kShape.nv + (config.use_contact_forces ? 6 * kShape.nbody : 0);
}

}  // namespace

Ant::Ant(const Config& config)
    : MujocoEnv("Ant-v4", model_file(config), kFrameSkip, observation_size(config)),
      config_(config) {
  require_shape(model(), kShape, id(), model_file(config));
  torso_ = body_id("torso");
  clipped_.resize(static_cast<size_t>(6 * model().nbody));
  set_default_camera({.distance = 4.0});
  Info& info = mutable_info();
  key_reward_forward_ = info.add_key("reward_forward");
  key_reward_ctrl_ = info.add_key("reward_ctrl");
  key_reward_survive_ = info.add_key("reward_survive");
  key_x_position_ = info.add_key("x_position");
  key_y_position_ = info.add_key("y_position");
  key_distance_from_origin_ = info.add_key("distance_from_origin");
  key_x_velocity_ = info.add_key("x_velocity");
  key_y_velocity_ = info.add_key("y_velocity");
  key_forward_reward_ = info.add_key("forward_reward");
}

void Ant::reset_model(Rng& rng) {
  const double scale = config_.reset_noise_scale;
  const std::vector<double> qpos = uniform_around(init_qpos(), -scale, scale, rng);
  const std::vector<double> qvel = normal_around(init_qvel(), scale, rng);
  set_state(qpos, qvel);
}

std::span<const double> Ant::contact_forces() const {
  return {data().cfrc_ext, static_cast<size_t>(6 * model().nbody)};
}

bool Ant::is_healthy() const {
  const auto finite = [](std::span<const double> values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
  };
  const double z = qpos()[2];
  return finite(qpos()) && finite(qvel()) && config_.healthy_z_range.low <= z &&
         z <= config_.healthy_z_range.high;
}

double Ant::contact_cost() {
  const std::span<const double> raw = contact_forces();
  const RangeKwarg& range = config_.contact_force_range;
  for (size_t i = 0; i < raw.size(); ++i) clipped_[i] = std::clamp(raw[i], range.low, range.high);
  return config_.contact_cost_weight * sum_of_squares(std::span<const double>(clipped_));
}

void Ant::observe(std::span<float> obs) const {
  const size_t skip = config_.exclude_current_positions_from_observation ? 2 : 0;
  ObservationWriter out(obs);
  out.put(qpos().subspan(skip)).put(qvel());
  if (config_.use_contact_forces)
    out.put_clipped(contact_forces(), config_.contact_force_range.low,
                    config_.contact_force_range.high);
}

// In ant_v4.py's order: the torso's position before and after the physics, then the rewards and
// costs. data.xpos after mj_step is neither the old nor the new state's: the model integrates
// with RK4, and MuJoCo leaves the positions of the last step's last stage; Gymnasium reads them so.
StepResult Ant::step(std::span<const float> action, std::span<float> obs) {
  const double* torso = body_xpos(torso_);
  const double x_before = torso[0], y_before = torso[1];
  if (!do_simulation(action)) return end_unstable(obs);
  const double x_after = torso[0], y_after = torso[1];
  const double x_velocity = (x_after - x_before) / dt();
  const double y_velocity = (y_after - y_before) / dt();
  const bool healthy = is_healthy();
  // float(is_healthy or terminate_when_unhealthy) * healthy_reward
  const double healthy_reward =
      static_cast<double>(healthy || config_.terminate_when_unhealthy) * config_.healthy_reward;
  const double rewards = x_velocity + healthy_reward;
  const double ctrl_cost = config_.ctrl_cost_weight * sum_of_squares(action);
  double costs = ctrl_cost;
  double reward_ctrl = -ctrl_cost;
  if (config_.use_contact_forces) {
    const double contact = contact_cost();
    costs += contact;
    reward_ctrl = -contact;  // Gymnasium's v4 overwrites info["reward_ctrl"] with this
  }
  observe(obs);
  Info& info = mutable_info();
  info.set(key_reward_forward_, x_velocity);
  info.set(key_reward_ctrl_, reward_ctrl);
  info.set(key_reward_survive_, healthy_reward);
  info.set(key_x_position_, x_after);
  info.set(key_y_position_, y_after);
  // np.linalg.norm of a float64 2-vector: sqrt(dot(x, x)), the dot left to right.
  info.set(key_distance_from_origin_, std::sqrt(x_after * x_after + y_after * y_after));
  info.set(key_x_velocity_, x_velocity);
  info.set(key_y_velocity_, y_velocity);
  info.set(key_forward_reward_, x_velocity);
  return {rewards - costs, config_.terminate_when_unhealthy && !healthy, false};
}

}  // namespace rlrun::mujoco
