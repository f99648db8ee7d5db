#include "rlrun/envs/mujoco/humanoid_standup.hpp"

#include <algorithm>

#include "rlrun/envs/mujoco/humanoid.hpp"
#include "rlrun/envs/mujoco/model_shape.hpp"

namespace rlrun::mujoco {

namespace {

constexpr int kFrameSkip = 5;
constexpr ModelShape kShape{.nq = 24, .nv = 23, .nu = 17, .nbody = 14};
constexpr double kResetNoise = 0.01;
// qpos[2:], qvel, cinert (10 per body), cvel (6), qfrc_actuator (nv), cfrc_ext (6): 376
constexpr int kObservationSize = kShape.nq - 2 + kShape.nv + 22 * kShape.nbody + kShape.nv;

std::string model_file(const HumanoidStandup::Config& config) {
  return model_path(config.xml_file.value, "humanoidstandup.xml");
}

}  // namespace

HumanoidStandup::HumanoidStandup(const Config& config)
    : MujocoEnv("HumanoidStandup-v4", model_file(config), kFrameSkip, kObservationSize) {
  require_shape(model(), kShape, id(), model_file(config));
  set_default_camera(
      {.trackbodyid = 1, .distance = 4.0, .lookat = {{0.0, 0.0, 0.8925}}, .elevation = -20.0});
  Info& info = mutable_info();
  key_reward_linup_ = info.add_key("reward_linup");
  key_reward_quadctrl_ = info.add_key("reward_quadctrl");
  key_reward_impact_ = info.add_key("reward_impact");
}

void HumanoidStandup::reset_model(Rng& rng) {
  const std::vector<double> qpos = uniform_around(init_qpos(), -kResetNoise, kResetNoise, rng);
  const std::vector<double> qvel = uniform_around(init_qvel(), -kResetNoise, kResetNoise, rng);
  set_state(qpos, qvel);
}

void HumanoidStandup::observe(std::span<float> obs) const {
  ObservationWriter out(obs);
  out.put(qpos().subspan(2)).put(qvel());
  put_body_dynamics(out, model(), data());
}

StepResult HumanoidStandup::step(std::span<const float> action, std::span<float> obs) {
  if (!do_simulation(action)) return end_unstable(obs);
  const double uph_cost = (qpos()[2] - 0) / model().opt.timestep;
  const std::span<const double> ctrl(data().ctrl, static_cast<size_t>(model().nu));
  const double quad_ctrl_cost = 0.1 * sum_of_squares(ctrl);
  const std::span<const double> contact(data().cfrc_ext, static_cast<size_t>(6 * model().nbody));
  // Python's min(cost, 10): the cost unless 10 is below it (so NaN stays NaN).
  const double quad_impact_cost = std::min(0.5e-6 * sum_of_squares(contact), 10.0);
  observe(obs);
  Info& info = mutable_info();
  info.set(key_reward_linup_, uph_cost);
  info.set(key_reward_quadctrl_, -quad_ctrl_cost);
  info.set(key_reward_impact_, -quad_impact_cost);
  return {uph_cost - quad_ctrl_cost - quad_impact_cost + 1, false, false};
}

}  // namespace rlrun::mujoco
