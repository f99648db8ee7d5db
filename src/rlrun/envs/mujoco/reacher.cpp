#include "rlrun/envs/mujoco/reacher.hpp"

#include <cmath>

#include "rlrun/envs/mujoco/model_shape.hpp"
#include "rlrun/envs/mujoco/numpy_math.hpp"

namespace rlrun::mujoco {

namespace {

constexpr int kFrameSkip = 2;
constexpr ModelShape kShape{.nq = 4, .nv = 4, .nu = 2};

std::string model_file(const Reacher::Config& config) {
  return model_path(config.xml_file.value, "reacher.xml");
}

}  // namespace

Reacher::Reacher(const Config& config)
    : MujocoEnv("Reacher-v4", model_file(config), kFrameSkip, 11),
      fingertip_(body_id("fingertip")),
      target_(body_id("target")) {
  require_shape(model(), kShape, id(), model_file(config));
  set_default_camera({.trackbodyid = 0});
  Info& info = mutable_info();
  key_reward_dist_ = info.add_key("reward_dist");
  key_reward_ctrl_ = info.add_key("reward_ctrl");
}

void Reacher::reset_model(Rng& rng) {
  std::vector<double> qpos = uniform_around(init_qpos(), -0.1, 0.1, rng);
  std::array<double, 2> goal{};
  do {
    goal = {rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)};
  } while (!(euclidean_norm(goal) < 0.2));
  qpos[2] = goal[0];
  qpos[3] = goal[1];
  std::vector<double> qvel = uniform_around(init_qvel(), -0.005, 0.005, rng);
  qvel[2] = 0.0;
  qvel[3] = 0.0;
  set_state(qpos, qvel);
}

std::array<double, 3> Reacher::fingertip_to_target() const {
  const double* tip = body_xpos(fingertip_);
  const double* target = body_xpos(target_);
  return {tip[0] - target[0], tip[1] - target[1], tip[2] - target[2]};
}

void Reacher::observe(std::span<float> obs) const {
  ObservationWriter out(obs);
  const std::span<const double> arm = qpos().first(2);
  for (double angle : arm) out.put(std::cos(angle));
  for (double angle : arm) out.put(std::sin(angle));
  out.put(qpos().subspan(2)).put(qvel().first(2)).put(fingertip_to_target());
}

StepResult Reacher::step(std::span<const float> action, std::span<float> obs) {
  // Gymnasium measures before simulating: the distance of the state the action is taken in.
  const double reward_dist = -euclidean_norm(fingertip_to_target());
  const double reward_ctrl = -sum_of_squares(action);  // a float32 in Gymnasium, widened here
  const double reward = reward_dist + reward_ctrl;
  if (!do_simulation(action)) return end_unstable(obs);
  observe(obs);
  Info& info = mutable_info();
  info.set(key_reward_dist_, reward_dist);
  info.set(key_reward_ctrl_, reward_ctrl);
  return {reward, false, false};
}

}  // namespace rlrun::mujoco
