#include "rlrun/envs/mujoco/humanoid.hpp"

#include <cmath>

#include "rlrun/core/pairwise_sum.hpp"
#include "rlrun/envs/mujoco/model_shape.hpp"

namespace rlrun::mujoco {

namespace {

constexpr int kFrameSkip = 5;
// The shipped model's sizes: 24 qpos (free joint 7, 17 hinges), 23 qvel, 14 bodies.
constexpr ModelShape kShape{.nq = 24, .nv = 23, .nu = 17, .nbody = 14};

std::string model_file(const Humanoid::Config& config) {
  return model_path(config.xml_file.value, "humanoid.xml");
}

int observation_size(const Humanoid::Config& config) {
  const int skip = config.exclude_current_positions_from_observation ? 2 : 0;
  // qpos, qvel, cinert (10 per body), cvel (6), qfrc_actuator (nv), cfrc_ext (6)
  return kShape.nq - skip + kShape.nv + 22 * kShape.nbody + kShape.nv;
}

}  // namespace

void put_body_dynamics(ObservationWriter& out, const mjModel& model, const mjData& data) {
  const auto values = [](const double* first, int count) {
    return std::span<const double>(first, static_cast<size_t>(count));
  };
  out.put(values(data.cinert, 10 * model.nbody))
      .put(values(data.cvel, 6 * model.nbody))
      .put(values(data.qfrc_actuator, model.nv))
      .put(values(data.cfrc_ext, 6 * model.nbody));
}

Humanoid::Humanoid(const Config& config)
    : MujocoEnv("Humanoid-v4", model_file(config), kFrameSkip, observation_size(config)),
      config_(config) {
  require_shape(model(), kShape, id(), model_file(config));
  total_mass_ = pairwise_sum<double>({model().body_mass, static_cast<size_t>(model().nbody)});
  set_default_camera(
      {.trackbodyid = 1, .distance = 4.0, .lookat = {{0.0, 0.0, 2.0}}, .elevation = -20.0});
  Info& info = mutable_info();
  key_reward_linvel_ = info.add_key("reward_linvel");
  key_reward_quadctrl_ = info.add_key("reward_quadctrl");
  key_reward_alive_ = info.add_key("reward_alive");
  key_x_position_ = info.add_key("x_position");
  key_y_position_ = info.add_key("y_position");
  key_distance_from_origin_ = info.add_key("distance_from_origin");
  key_x_velocity_ = info.add_key("x_velocity");
  key_y_velocity_ = info.add_key("y_velocity");
  key_forward_reward_ = info.add_key("forward_reward");
}

void Humanoid::reset_model(Rng& rng) {
  const double scale = config_.reset_noise_scale;
  const std::vector<double> qpos = uniform_around(init_qpos(), -scale, scale, rng);
  const std::vector<double> qvel = uniform_around(init_qvel(), -scale, scale, rng);
  set_state(qpos, qvel);
}

bool Humanoid::is_healthy() const {
  const double z = qpos()[2];
  return config_.healthy_z_range.low < z && z < config_.healthy_z_range.high;
}

// numpy sums axis 0 of the (nbody, 3) products row after row, from the first row (the world's).
std::array<double, 2> Humanoid::mass_center() const {
  const mjModel& m = model();
  const double* xipos = data().xipos;
  std::array<double, 2> sum = {m.body_mass[0] * xipos[0], m.body_mass[0] * xipos[1]};
  for (int b = 1; b < m.nbody; ++b) {
    sum[0] += m.body_mass[b] * xipos[3 * b];
    sum[1] += m.body_mass[b] * xipos[3 * b + 1];
  }
  return {sum[0] / total_mass_, sum[1] / total_mass_};
}

void Humanoid::observe(std::span<float> obs) const {
  const size_t skip = config_.exclude_current_positions_from_observation ? 2 : 0;
  ObservationWriter out(obs);
  out.put(qpos().subspan(skip)).put(qvel());
  put_body_dynamics(out, model(), data());
}

// In humanoid_v4.py's order: the centre of mass before and after the physics, then the costs and
// rewards. data.xipos after mj_step is neither the old nor the new state's: the model integrates
// with RK4, and MuJoCo leaves the positions of the last step's last stage; Gymnasium reads them so.
StepResult Humanoid::step(std::span<const float> action, std::span<float> obs) {
  const std::array<double, 2> before = mass_center();
  if (!do_simulation(action)) return end_unstable(obs);
  const std::array<double, 2> after = mass_center();
  const double x_velocity = (after[0] - before[0]) / dt();
  const double y_velocity = (after[1] - before[1]) / dt();
  // Gymnasium's control cost reads data.ctrl: the action in float64, summed in float64.
  const std::span<const double> ctrl(data().ctrl, static_cast<size_t>(model().nu));
  const double ctrl_cost = config_.ctrl_cost_weight * sum_of_squares(ctrl);
  const double forward_reward = config_.forward_reward_weight * x_velocity;
  const bool healthy = is_healthy();
  // float(is_healthy or terminate_when_unhealthy) * healthy_reward
  const double healthy_reward =
      static_cast<double>(healthy || config_.terminate_when_unhealthy) * config_.healthy_reward;
  observe(obs);
  Info& info = mutable_info();
  info.set(key_reward_linvel_, forward_reward);
  info.set(key_reward_quadctrl_, -ctrl_cost);
  info.set(key_reward_alive_, healthy_reward);
  info.set(key_x_position_, after[0]);
  info.set(key_y_position_, after[1]);
  // np.linalg.norm of a float64 2-vector: sqrt(dot(x, x)), the dot left to right.
  info.set(key_distance_from_origin_, std::sqrt(after[0] * after[0] + after[1] * after[1]));
  info.set(key_x_velocity_, x_velocity);
  info.set(key_y_velocity_, y_velocity);
  info.set(key_forward_reward_, forward_reward);
  return {(forward_reward + healthy_reward) - ctrl_cost,
          config_.terminate_when_unhealthy && !healthy, false};
}

}  // namespace rlrun::mujoco
